"""coatsim.geometry stage."""
