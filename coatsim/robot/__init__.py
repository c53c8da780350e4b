"""coatsim.robot stage."""
