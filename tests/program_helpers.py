"""Shared builders and path comparison for the programs-stage tests."""

from __future__ import annotations

import math

import numpy as np

from coatsim.geometry.polysegment import Polysegment, chain
from coatsim.languages.kawasaki_as.writer import MAX_ARC_SWEEP_DEG
from coatsim.path.arcs import sample_move
from coatsim.geometry.space.pose import rotation_angle
from coatsim.path.placement import PlacedPath
from coatsim.path.toolpath import ToolPath


def roundrect(width: float = 150.0, height: float = 80.0, radius: float = 10.0) -> Polysegment:
    """Closed rounded rectangle centred on the origin, counter-clockwise: 4 lines + 4 arcs."""
    k, quarter = 1.0 / radius, math.pi / 2 * radius
    segs = chain((-width / 2 + radius, -height / 2), 0.0, [0, k, 0, k, 0, k, 0, k],
                 [width - 2 * radius, quarter, height - 2 * radius, quarter] * 2)
    return Polysegment(segs, closed=True)


def arc_spiral(turns: int = 3, pieces_per_turn: int = 6, r0: float = 5.0, growth: float = 1.25) -> Polysegment:
    """Open G1 spiral made only of arcs whose radius grows piece by piece."""
    curvatures, lengths = [], []
    radius = r0
    for _ in range(turns * pieces_per_turn):
        sweep = 2 * math.pi / pieces_per_turn
        curvatures.append(1.0 / radius)
        lengths.append(radius * sweep)
        radius *= growth
    return Polysegment(chain((0.0, 0.0), 0.0, curvatures, lengths))


def placed_pieces(path: PlacedPath) -> list:
    """The placed segments as the writer emits them (arcs split at the sweep limit)."""
    out = []
    for seg in path.segments:
        out.extend(seg.split(math.radians(MAX_ARC_SWEEP_DEG)) if seg.is_arc else [seg])
    return out


def path_errors(path: PlacedPath, toolpath: ToolPath, samples: int = 21) -> tuple[float, float, float]:
    """Largest position error (mm), tangent error (rad) and tool rotation error (rad) between
    the placed path and the moves read back (those between the move down to the stand-off and
    the depart), compared piece by piece."""
    pieces = placed_pieces(path)
    moves = toolpath.moves[2:-1]
    assert len(moves) == len(pieces)
    u = np.linspace(0.0, 1.0, samples)
    dp = dt = dr = 0.0
    for move, piece in zip(moves, pieces):
        p1, t1 = sample_move(move, u)
        p2, t2 = piece.point_tangent(u)
        dp = max(dp, float(np.linalg.norm(p1 - p2, axis=1).max()))
        cross = np.linalg.norm(np.cross(t1, t2), axis=1)
        dt = max(dt, float(np.arctan2(cross, (t1 * t2).sum(axis=1)).max()))
        for a, b in ((move.start, piece.start), (move.end, piece.end)):
            dr = max(dr, rotation_angle(a.rotation, b.rotation))
    return dp, dt, dr


def check_as(paths, gun_signal: int = 1, program=None, *, inputs=None, kinematics=None, gun_tcp=None, variables=None):
    """check-program of Kawasaki AS files (the language-neutral report of its reading)."""
    from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
    from coatsim.path.check import check_program
    from coatsim.path.language import ReadOptions

    options = ReadOptions(gun_signal=gun_signal, program=program, inputs=inputs or {}, kinematics=kinematics,
                          variables=variables or {})
    return check_program(paths, KAWASAKI_AS, options, gun_tcp=gun_tcp)


def convert_as(paths, options, **kwargs):
    """convert of Kawasaki AS files (in place, or standalone in AS unless ``target`` is given)."""
    from coatsim.languages.kawasaki_as.language import KAWASAKI_AS
    from coatsim.path.convert import convert_program

    return convert_program(paths, options, language=KAWASAKI_AS, **kwargs)
