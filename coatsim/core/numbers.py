"""Numbers as program text writes them: fixed point, no negative zero, trailing zeros dropped.

Coordinates are the program's only record of the path, and the twin executes the text.
Rounding a coordinate by e tilts the tangent of a segment of length L by up to ~10 e / L
(three-point arcs are the worst case), and fitted polysegments can hold segments of
0.1 mm. 4 decimals would keep positions within 1e-4 mm but tilt the tangent of a 1 mm arc
by ~2e-4 rad; 8 decimals (e <= 5e-9 mm, 11 significant digits at a metre, well within a
double) keep positions within 1e-8 mm and tangents within 1e-6 rad down to 0.05 mm
segments.
(Controllers save 3 decimals and store less; the extra digits are for the twin.)
"""

from __future__ import annotations

MM_DECIMALS = 8


def fmt(value: float, decimals: int) -> str:
    """Fixed-point text without negative zero."""
    text = f"{value:.{decimals}f}"
    return text[1:] if text.startswith("-") and float(text) == 0.0 else text


def fmt_short(value: float, decimals: int = MM_DECIMALS) -> str:
    """Fixed-point text with trailing zeros removed ("50", "0.5")."""
    text = fmt(value, decimals)
    return text.rstrip("0").rstrip(".") if "." in text else text

