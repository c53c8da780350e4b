"""coatsim.program stage."""
