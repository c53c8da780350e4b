"""coatsim.report stage."""
