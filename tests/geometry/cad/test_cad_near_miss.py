"""Drawings whose ends nearly meet, as drawing programs write them: coordinates rounded to a few
decimals (Inkscape's relative paths, Illustrator's points, LibreCAD's arc angles, a plotter
tool's hundreds of short strokes). Ends a few micrometres apart are joined, the largest gap
closed is noted, and the result stays within the tolerance of the drawing as designed."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from coatsim.geometry.cad import segment_drawing

from cad_helpers import max_distance, write_dxf, write_svg

TOL = 0.1
PX_PER_MM = 96 / 25.4


def _gap_note(part) -> float:
    """The largest gap closed, from the note saying so."""
    (note,) = [n for n in part.notes if "largest gap closed" in n]
    return float(re.search(r"largest gap closed is ([0-9.e-]+) mm", note).group(1))


def _round_rect(x: float, y: float, w: float, h: float, r: float, n: int = 400) -> np.ndarray:
    """Dense points (mm, y down as in the SVG's user units) of a rounded rectangle, closed."""
    out = []
    corners = [(x + w - r, y + r, -math.pi / 2), (x + w - r, y + h - r, 0.0), (x + r, y + h - r, math.pi / 2),
               (x + r, y + r, math.pi)]
    for cx, cy, a0 in corners:
        a = np.linspace(a0, a0 + math.pi / 2, n // 4)
        out.append(np.column_stack((cx + r * np.cos(a), cy + r * np.sin(a))))
    pts = np.vstack(out)
    return np.vstack((pts, pts[:1]))


def _y_up(points: np.ndarray) -> np.ndarray:
    return np.column_stack((points[:, 0], -points[:, 1]))


def test_inkscape_relative_paths_with_three_decimals(tmp_path):
    """A rounded rectangle drawn as four open paths (a side and a corner each) in relative
    coordinates rounded to 3 decimals, inside a translated layer: every end misses the next
    path's start by the rounding."""
    x, y, w, h, r = 20.0, 30.0, 120.0, 70.0, 15.0
    k = 0.5523 * r  # Bézier handle of a quarter circle
    sides = [
        ((x + r, y), [(w - 2 * r, 0)], [(k, 0, r, r - k, r, r)]),
        ((x + w, y + r), [(0, h - 2 * r)], [(0, k, -(r - k), r, -r, r)]),
        ((x + w - r, y + h), [(-(w - 2 * r), 0)], [(-k, 0, -r, -(r - k), -r, -r)]),
        ((x, y + h - r), [(0, -(h - 2 * r))], [(0, -k, r - k, -r, r, -r)]),
    ]
    body = []
    for (sx, sy), lines, curves, (dx, dy) in zip(*zip(*sides), [(0.0031, -0.0022), (-0.0027, 0.0014), (0.0019, 0.0033), (-0.0034, -0.0008)]):
        sx, sy = sx + dx, sy + dy  # relative steps rounded to 3 decimals add up differently along each path
        d = f"m {sx:.3f},{sy:.3f} " + " ".join(f"l {a:.3f},{b:.3f}" for a, b in lines) + " " + \
            " ".join("c " + " ".join(f"{v:.3f}" for v in c) for c in curves)
        body.append(f'<path style="fill:none;stroke:#000000;stroke-width:0.26458" d="{d}"/>')
    svg = ('<g inkscape:groupmode="layer" inkscape:label="Layer 1" transform="translate(0.5,-0.25)">'
           + "\n".join(body) + "</g>")
    part = segment_drawing(write_svg(tmp_path, svg, attrs='width="200mm" height="150mm" viewBox="0 0 200 150"'), TOL)
    assert len(part.contours) == 1 and part.contours[0].polysegment.closed
    assert 0.0005 < _gap_note(part) < TOL / 2
    design = _y_up(_round_rect(x + 0.5, y - 0.25, w, h, r))
    assert part.contours[0].max_deviation_mm <= TOL
    assert max_distance(design, part.contours[0].polysegment) <= TOL + 0.002  # Béziers approximate the quarter circles


def test_illustrator_points_with_two_decimals(tmp_path):
    """Illustrator writes points (1/72 in) with two decimals: 0.01 pt is 3.5 µm. A hexagonal
    nut outline and its bolt circle, each side a separate <line>, the circle as two <path>
    half arcs whose ends are rounded."""
    pt = 25.4 / 72  # mm per point
    cx, cy, big, hole = 200.0, 200.0, 120.0, 45.0  # in points
    corners = [(cx + big * math.cos(a), cy + big * math.sin(a)) for a in np.arange(6) * math.pi / 3 + 0.01]
    body = [f'<line class="st0" x1="{a[0]:.2f}" y1="{a[1]:.2f}" x2="{b[0] + 0.004:.2f}" y2="{b[1] - 0.004:.2f}"/>'
            for a, b in zip(corners, corners[1:] + corners[:1])]
    p0, p1 = (cx + hole, cy + 0.003), (cx - hole, cy - 0.004)
    body += [f'<path class="st0" d="M{p0[0]:.2f},{p0[1]:.2f}A{hole:.2f},{hole:.2f} 0 0 1 {p1[0]:.2f},{p1[1]:.2f}"/>',
             f'<path class="st0" d="M{p1[0] + 0.006:.2f},{p1[1]:.2f}A{hole:.2f},{hole:.2f} 0 0 1 {p0[0]:.2f},{p0[1] + 0.007:.2f}"/>']
    attrs = f'version="1.1" x="0px" y="0px" width="{400 * pt:.4f}mm" height="{400 * pt:.4f}mm" viewBox="0 0 400 400"'
    part = segment_drawing(write_svg(tmp_path, "\n".join(body), attrs=attrs), TOL)
    assert len(part.contours) == 2 and all(c.polysegment.closed for c in part.contours)
    assert _gap_note(part) < TOL / 2
    hexagon = next(c for c in part.contours if c.polysegment.n_lines == 6)
    assert len(hexagon.polysegment.corners) == 6
    exact = np.array(corners + corners[:1]) * pt * np.array([1.0, -1.0])
    dense = np.vstack([a + np.linspace(0, 1, 200)[:, None] * (b - a) for a, b in zip(exact[:-1], exact[1:])])
    assert max_distance(dense, hexagon.polysegment) <= TOL


def test_plotter_calibration_sheet_of_three_hundred_strokes(tmp_path):
    """A plotter calibration sheet: 100 squares, 100 circles of quadratic and cubic Béziers,
    and 100 crosses, every shape drawn as separate strokes whose ends are rounded to 0.01 px
    (2.6 µm) and nudged as a pen-plotting tool's path joiner leaves them."""
    rng = np.random.default_rng(7)
    body = []
    for k in range(100):
        ox, oy = 40.0 + 70.0 * (k % 10), 40.0 + 70.0 * (k // 10)
        a, b, c, d = (ox, oy), (ox + 40, oy), (ox + 40, oy + 40), (ox, oy + 40)
        nudge = lambda p: (p[0] + rng.uniform(-0.012, 0.012), p[1] + rng.uniform(-0.012, 0.012))  # noqa: E731
        body.append(f'<path d="M {a[0]:.2f} {a[1]:.2f} L {b[0]:.2f} {b[1]:.2f} L {c[0]:.2f} {c[1]:.2f}"/>')
        e, f = nudge(c), nudge(a)
        body.append(f'<path d="M {e[0]:.2f} {e[1]:.2f} L {d[0]:.2f} {d[1]:.2f} L {f[0]:.2f} {f[1]:.2f}"/>')
    for k in range(100):
        cx, cy, r = 40.0 + 70.0 * (k % 10) + 20, 760.0 + 70.0 * (k // 10) + 20, 15.0
        h = 0.5523 * r
        top, bottom = (cx, cy - r), (cx + rng.uniform(-0.01, 0.01), cy + r)
        body.append(f'<path d="M {top[0]:.2f} {top[1]:.2f} C {cx + h:.2f} {cy - r:.2f} {cx + r:.2f} {cy - h:.2f} '
                    f'{cx + r:.2f} {cy:.2f} C {cx + r:.2f} {cy + h:.2f} {cx + h:.2f} {cy + r:.2f} {bottom[0]:.2f} {bottom[1]:.2f}"/>')
        body.append(f'<path d="M {bottom[0] + 0.01:.2f} {bottom[1]:.2f} Q {cx - r:.2f} {cy + r:.2f} {cx - r:.2f} {cy:.2f} '
                    f'Q {cx - r:.2f} {cy - r:.2f} {top[0] + rng.uniform(-0.01, 0.01):.2f} {top[1]:.2f}"/>')
    for k in range(100):
        cx, cy = 40.0 + 70.0 * (k % 10) + 20, 1480.0 + 70.0 * (k // 10) + 20
        body.append(f'<path d="M {cx - 10:.2f} {cy:.2f} L {cx + 10:.2f} {cy:.2f} M {cx:.2f} {cy - 10:.2f} L {cx:.2f} {cy + 10:.2f}"/>')
    svg = '<g style="fill:none;stroke:black">' + "\n".join(body) + "</g>"
    path = write_svg(tmp_path, svg, attrs='width="2200px" height="2200px" viewBox="0 0 2200 2200"')
    part = segment_drawing(path, TOL)
    squares = [c for c in part.contours if c.polysegment.n_lines == 4 and c.polysegment.closed]
    circles = [c for c in part.contours if c.polysegment.closed and c.polysegment.n_arcs > 0]
    assert len(squares) == 100 and len(circles) == 100
    assert 0.0005 < _gap_note(part) < TOL / 2
    assert max(c.max_deviation_mm for c in part.contours) <= TOL


def test_librecad_arcs_with_rounded_angles(tmp_path):
    """LibreCAD-style DXF: a slotted plate of LINEs and ARCs whose angles are written with two
    decimals (the arc ends then miss the lines by up to 5 µm) and whose line ends carry four."""
    def draw(msp, doc):
        r, length = 12.5, 80.0
        r4 = lambda v: round(v, 4)  # noqa: E731
        msp.add_line((r4(0.0), r4(-r)), (r4(length), r4(-r)))
        msp.add_arc((length, 0.0), r, round(-90.0 + 0.004, 2) + 0.003, round(90.0 - 0.003, 2))
        msp.add_line((r4(length), r4(r)), (r4(0.0), r4(r)))
        msp.add_arc((0.0, 0.0), r, 90.004, 270.0 - 0.004)
        outline = [(-30.0, -40.0), (110.0, -40.0), (110.0, 40.0), (-30.0, 40.0)]
        for a, b in zip(outline, outline[1:] + outline[:1]):
            msp.add_line((a[0] + 0.0013, a[1]), (b[0], b[1] - 0.0011))

    part = segment_drawing(write_dxf(tmp_path, draw, version="R2000"), TOL)
    assert len(part.contours) == 2 and all(c.polysegment.closed for c in part.contours)
    slot = next(c for c in part.contours if c.polysegment.n_arcs >= 2)
    # the rounded angles break tangency by 0.004 deg: the arcs are fitted tangent to the lines
    # (one of them in two pieces) rather than kept with four corners, four stops of the robot
    assert slot.polysegment.n_segments <= 5 and not slot.polysegment.corners and slot.max_deviation_mm <= TOL
    assert 0.0005 < _gap_note(part) < TOL / 2


@pytest.mark.parametrize("gap,contours", [(0.03, 1), (0.07, 2), (0.2, 2)])
def test_a_gap_is_closed_only_where_the_result_stays_within_the_tolerance(tmp_path, gap, contours):
    """An open outline of two polylines meeting with a gap: closed below half the tolerance
    (the deviation from the drawing, joins included, stays within it), left as two contours
    above it (named in a note while closer than the tolerance)."""
    body = (f'<polyline points="10,10 60,10 60,40"/>'
            f'<polyline points="{60 + gap},40 90,40 90,70"/>')
    part = segment_drawing(write_svg(tmp_path, f'<g style="fill:none;stroke:black">{body}</g>'), TOL)
    assert len(part.contours) == contours
    assert max(c.max_deviation_mm for c in part.contours) <= TOL
    named = any("not joined" in n for n in part.notes)
    assert named == (contours == 2 and gap < TOL)
