"""Benchmark of the CAD input: per drawing, contours, pieces in, segments out, deviation, seconds.

    python scripts/bench_cad.py [FOLDER_OR_FILE ...] [--tol 0.1] [--no-generated]

Every .dxf and .svg under the folders given (e.g. ../shared/corpus) is read, chained and
segmented at --tol; a drawing that is refused prints its one-line error instead. Generated
drawings are added unless --no-generated: 1 000 native entities (lines, arcs, circles, bulged
polylines: slotted plates on a grid) and 200 splines, written with ezdxf into a temporary
folder. Prints a Markdown table; never asserts.
"""

from __future__ import annotations

import argparse
import math
import tempfile
import time
from pathlib import Path

from coatsim.core.errors import CoatsimError
from coatsim.geometry.cad import segment_drawing
from coatsim.geometry.cad.drawing import DRAWING_SUFFIXES


def generated_native(folder: Path, n_entities: int = 1000) -> Path:
    """Slotted plates on a grid: each a bulged LWPOLYLINE outline, a CIRCLE, and a slot of
    two LINEs and two ARCs (one line drawn backwards): 7 entities per plate, padded with
    CIRCLEs to ``n_entities``."""
    import ezdxf

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    b = math.tan(math.pi / 8)
    count, k = 0, 0
    while count + 7 <= n_entities:
        x, y = 60.0 * (k % 12), 50.0 * (k // 12)
        msp.add_lwpolyline([(x, y, 0, 0, 0), (x + 40, y, 0, 0, b), (x + 45, y + 5), (x + 45, y + 35, 0, 0, b),
                            (x + 40, y + 40), (x, y + 40)], format="xyseb", close=True)
        msp.add_circle((x + 12, y + 20), 6)
        msp.add_line((x + 25, y + 10), (x + 35, y + 10))
        msp.add_arc((x + 35, y + 14), 4, -90, 90)
        msp.add_line((x + 25, y + 18), (x + 35, y + 18))
        msp.add_arc((x + 25, y + 14), 4, 90, 270)
        msp.add_arc((x + 22, y + 30), 3, 0, 200)
        count, k = count + 7, k + 1
    for j in range(n_entities - count):
        msp.add_circle((-20.0, 10.0 * j), 3)
    path = folder / f"generated_{n_entities}_native.dxf"
    doc.saveas(path)
    return path


def generated_splines(folder: Path, n: int = 200) -> Path:
    """``n`` open cubic splines through five fit points each, on a grid."""
    import ezdxf

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    for k in range(n):
        x, y = 80.0 * (k % 20), 30.0 * (k // 20)
        msp.add_spline(fit_points=[(x, y), (x + 15, y + 10 + k % 7), (x + 30, y - 5), (x + 45, y + 8), (x + 60, y)])
    path = folder / f"generated_{n}_splines.dxf"
    doc.saveas(path)
    return path


def generated_mixed(folder: Path, n: int = 20) -> Path:
    """``n`` closed outlines mixing native and free-form pieces joined tangentially: a line, a
    spline leaving and meeting lines along their directions, half an ellipse, a closing half circle."""
    import ezdxf

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    for k in range(n):
        x, y = 120.0 * (k % 5), 80.0 * (k // 5)
        msp.add_line((x + 10, y), (x + 20, y))
        msp.add_open_spline([(x + 20, y), (x + 35, y), (x + 45, y + 15 + k % 4), (x + 60, y + 10), (x + 75, y + 10)])
        msp.add_line((x + 75, y + 10), (x + 90, y + 10))
        msp.add_ellipse((x + 90, y + 25), major_axis=(0, -15), ratio=0.5, start_param=0, end_param=math.pi)
        msp.add_line((x + 90, y + 40), (x + 10, y + 40))
        msp.add_arc((x + 10, y + 20), 20, 90, 270)
    path = folder / f"generated_{n}_mixed_parts.dxf"
    doc.saveas(path)
    return path


def drawings(paths: list[str]) -> list[Path]:
    found: list[Path] = []
    for item in paths:
        p = Path(item)
        if p.is_dir():
            found += sorted(q for q in p.rglob("*") if q.suffix.lower() in DRAWING_SUFFIXES)
        else:
            found.append(p)
    return found


def row(path: Path, tol: float) -> str:
    started = time.perf_counter()
    try:
        part = segment_drawing(path, tol)
    except CoatsimError as exc:
        return f"| {path.name} | refused: {str(exc).replace(str(path), 'file')} | | | | | | |"
    seconds = time.perf_counter() - started
    st = part.stats()
    return (f"| {path.name} | {st['n_contours']} ({st['n_closed']} closed) | {st['input_primitives']} | "
            f"{st['n_segments']} ({st['n_arcs']} arcs, {st['n_lines']} lines) | {st['n_corners']} | "
            f"{st['max_deviation_mm']:.4g} | {st['max_tangent_break_deg']:.2g} | {seconds:.2f} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("paths", nargs="*", help="folders or drawing files")
    parser.add_argument("--tol", type=float, default=0.1, help="tolerance sigma, mm")
    parser.add_argument("--no-generated", action="store_true", help="skip the generated drawings")
    args = parser.parse_args()
    print(f"tolerance {args.tol:g} mm, join tolerance {args.tol / 100:g} mm\n")
    print("| drawing | contours | pieces in | segments out | corners | deviation mm | tangent break deg | seconds |")
    print("|---|---|---|---|---|---|---|---|")
    for path in drawings(args.paths):
        print(row(path, args.tol), flush=True)
    if not args.no_generated:
        with tempfile.TemporaryDirectory() as tmp:
            for path in (generated_native(Path(tmp)), generated_mixed(Path(tmp)), generated_splines(Path(tmp))):
                print(row(path, args.tol), flush=True)


if __name__ == "__main__":
    main()
