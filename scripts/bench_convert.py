"""convert: CPU seconds of rewriting a taught program of N and 2N LMOVEs in place (read, fit,
orient, write, read back and measure), and the exponent against N, for a path in a plane (an
ellipse, the tool fixed) and in space (a wavy pass over a cylinder, the gun on its normal turning
with it); the moves out, the deviation and the tool's angle from the original's. Prints only;
never asserts.

    python scripts/bench_convert.py [N]   (default 500 moves)
"""

from __future__ import annotations

import math
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from scaling import cpu, report  # noqa: E402

TOL_MM = 0.1


def _program(points: np.ndarray, rotations: np.ndarray) -> str:
    from coatsim.geometry.space.rotations import matrix_to_oat

    trans = "\n".join(f"c[{i}] " + " ".join(f"{v:.4f}" for v in (*p, *matrix_to_oat(r)))
                      for i, (p, r) in enumerate(zip(points, rotations)))
    body = "\n".join(f"  LMOVE c[{i}]" for i in range(1, len(points)))
    return (f".PROGRAM taught()\n  SPEED 200 MM/S ALWAYS\n  JMOVE c[0]\n  BREAK\n  SIGNAL 1\n{body}\n"
            f"  BREAK\n  SIGNAL -1\n.END\n.TRANS\n{trans}\n.END\n")


def planar(n: int) -> tuple[np.ndarray, np.ndarray]:
    """An ellipse 200 x 100 mm at z 300, the tool pointing down."""
    t = np.linspace(0.0, 2 * math.pi, n + 1)
    points = np.column_stack((700 + 100 * np.cos(t), 50 * np.sin(t), np.full_like(t, 300.0)))
    return points, np.broadcast_to(np.diag([1.0, -1.0, -1.0]), (n + 1, 3, 3))


def space(n: int) -> tuple[np.ndarray, np.ndarray]:
    """A pass over a cylinder of radius 150 mm, waving 20 mm across, the gun on the normal at
    80 mm, its x turning with the wave."""
    theta = np.radians(np.linspace(-60.0, 60.0, n + 1))
    points, rotations = [], []
    for t in theta:
        normal = np.array([math.sin(t), 0.0, math.cos(t)])
        points.append(np.array([700 + 150 * math.sin(t), 20 * math.sin(3 * t), 100 + 150 * math.cos(t)]) + 80 * normal)
        z = -normal
        x = np.array([math.cos(t), 0.3 * math.cos(3 * t), -math.sin(t)])
        x = x - (x @ z) * z
        x /= np.linalg.norm(x)
        rotations.append(np.column_stack((x, np.cross(z, x), z)))
    return np.array(points), np.array(rotations)


def main(n: int) -> None:
    from coatsim.languages.registry import language
    from coatsim.path.convert import ConvertOptions, convert_program

    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for name, make in (("planar ellipse", planar), ("cylinder pass (space)", space)):
            timed = {}
            for size in (n, 2 * n):
                path = Path(folder) / f"{name.split()[0]}_{size}.as"
                path.write_text(_program(*make(size)))
                seconds, result = cpu(lambda: convert_program(path, ConvertOptions(TOL_MM),
                                                              language=language("kawasaki-as")))
                (r,) = result.paths
                timed[size] = seconds
                print(f"{name}, {size} moves -> {r.moves_after} ({r.n_lines} lines + {r.n_arcs} arcs), deviation "
                      f"{r.deviation_mm:.4f} mm, tool within {r.tool_angle_deg:.2f} deg, {seconds:.2f} CPU s")
            rows.append((f"convert in place: {name}", n, timed[n], 2 * n, timed[2 * n]))
    report(f"convert, sigma {TOL_MM} mm", rows, unit="moves")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 500)
