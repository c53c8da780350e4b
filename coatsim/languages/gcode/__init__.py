"""G-code (RS274/NGC as LinuxCNC reads it, the common subset of Fanuc-style CNC controls)."""
