"""coatsim.spray stage."""
