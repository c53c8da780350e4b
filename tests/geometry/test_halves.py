"""An open sparse run cut in halves (coatsim.geometry.halves): the halves' chain keeps the
run's tolerance and pinned end tangents, joins G1 where it lists no corner, and is never
longer than the run's own lines."""

from __future__ import annotations

import math

import numpy as np
import pytest

from coatsim.geometry.deviation import hausdorff
from coatsim.geometry.fit import fit_run
from coatsim.geometry.halves import MIN_SPLIT_MOVES, in_halves
from coatsim.geometry.limits import fit_limits
from coatsim.geometry.polysegment import Polysegment
from coatsim.geometry.sparse import taught_lines

from test_taught_paths import _taught_log_spiral

G1_RAD = 1e-9


def _breaks(segments) -> list[int]:
    """Junctions (k: end of segment k) where the tangent turns."""
    return [k for k, (a, b) in enumerate(zip(segments[:-1], segments[1:]))
            if abs(math.remainder(b.start_heading - a.end_heading, 2 * math.pi)) > G1_RAD]


def _check(pts: np.ndarray, tol: float, **pins):
    found = in_halves(pts, tol, fit_limits(pts, False, tol, None, None), fit_run, **pins)
    poly = Polysegment(found.segments)
    assert hausdorff(pts, poly).hausdorff <= tol
    assert found.deviation_mm == pytest.approx(hausdorff(pts, poly).hausdorff)
    assert set(_breaks(found.segments)) <= set(found.corners)
    assert all(a.end == b.start for a, b in zip(found.segments[:-1], found.segments[1:]))
    assert found.segments[0].start == tuple(pts[0]) and found.segments[-1].end == tuple(pts[-1])
    assert len(found.segments) <= len(taught_lines(pts, False, tol).segments)
    return found


@pytest.mark.parametrize("count", [
    pytest.param(12, marks=pytest.mark.xfail(strict=True, reason=(
        "measured limit: with 12 points the first half (8 points and half the next edge), its start pinned, finds no "
        "chain under its caps and keeps 3 of its lines; the whole run pinned fits with 4 arcs"))),
    20, 30])
def test_pinned_end_tangents_are_kept_by_the_halves(count):
    """A log spiral taught with 12-30 points, its end tangents pinned to those of its own
    unpinned chain (so some chain keeps them): the halves start and end on them, and join G1."""
    pts, tol = _taught_log_spiral(count, 0.7, 0, jitter=0.0)
    free = fit_run(pts, tol, False, fit_limits(pts, False, tol, None, None))
    start, end = free.segments[0].start_heading, free.segments[-1].end_heading
    found = _check(pts, tol, start_heading=start, end_heading=end)
    assert not found.corners and len(found.segments) < count - 1
    assert abs(math.remainder(found.segments[0].start_heading - start, 2 * math.pi)) <= G1_RAD
    assert abs(math.remainder(found.segments[-1].end_heading - end, 2 * math.pi)) <= G1_RAD


def test_a_run_too_short_to_cut_keeps_its_lines():
    """Fewer moves than MIN_SPLIT_MOVES: the run's own lines, with their note."""
    pts, tol = _taught_log_spiral(MIN_SPLIT_MOVES, 0.7, 1)
    found = in_halves(pts, tol, fit_limits(pts, False, tol, None, None), fit_run)
    assert found == taught_lines(pts, False, tol)
