"""Geometry of space: the pose type (``pose``), robot languages' rotation conventions
(``rotations``), 3-D lines and arcs (``primitives``), and the 3-D fit of space curves."""
