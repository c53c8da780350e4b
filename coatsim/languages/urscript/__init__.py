"""Universal Robots URScript (``.script`` files, as Polyscope, RoboDK and hand-written programs hold them)."""
