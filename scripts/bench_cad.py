"""Benchmark of the CAD input: per drawing, contours, pieces in, free-form fits, segments out,
deviation and CPU seconds (all, and in the free-form fits), then the exponent against size.

    python scripts/bench_cad.py [FOLDER_OR_FILE ...] [--tol 0.1] [--no-generated]

Every .dxf and .svg under the folders given (e.g. ../shared/corpus) is read, chained and
segmented at --tol; a drawing that is refused prints its one-line error instead. Generated
drawings are added unless --no-generated, written into a temporary folder: 1 000 native
entities (lines, arcs, circles, bulged polylines: slotted plates on a grid), 200 splines and
20 mixed outlines (ezdxf), and text outlines as SVG paths of Béziers (matplotlib's TextPath:
a greeting in a sans and a serif face, cubic or quadratic, at letter heights and coordinate
precisions fonts are exported with). The exponent is log(t2 / t1) / log(n2 / n1) between
a text and a longer one (n: pieces). CPU seconds are this process's. Prints Markdown tables;
never asserts.
"""

from __future__ import annotations

import argparse
import math
import tempfile
import time
from pathlib import Path

import coatsim.geometry.cad.contour_fit as contour_fit
from coatsim.core.errors import CoatsimError
from coatsim.geometry.cad import segment_drawing
from coatsim.geometry.cad.drawing import DRAWING_SUFFIXES

GREETING = "Season's greetings\nfrom coatsim"  # 568 pieces: 396 Béziers and 172 lines, 40 outlines
SHORT_GREETING = "Season's greetings"


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


def text_outlines(folder: Path, text: str, name: str, family: str = "DejaVu Sans", height_mm: float = 30.0,
                  decimals: int = 4, cubic: bool = True) -> Path:
    """``text`` as closed glyph outlines in an SVG (mm): TrueType quadratic Béziers, written as
    such ('Q') or raised to cubics ('C'), lines as 'L', coordinates rounded to ``decimals``."""
    from matplotlib.font_manager import FontProperties
    from matplotlib.path import Path as MplPath
    from matplotlib.textpath import TextPath

    f = lambda *xy: " ".join(f"{v:.{decimals}f}" for p in xy for v in (p[0], -p[1]))  # noqa: E731 (y down in SVG)
    paths = []
    for row, line in enumerate(text.split("\n")):
        glyphs = TextPath((0.0, -1.3 * height_mm * row), line, size=height_mm, prop=FontProperties(family=family))
        vertices, codes, d, k, here = glyphs.vertices, glyphs.codes, [], 0, None
        while k < len(codes):
            code = codes[k]
            if code == MplPath.MOVETO:
                d.append(f"M {f(vertices[k])}")
                here, k = vertices[k], k + 1
            elif code == MplPath.LINETO:
                d.append(f"L {f(vertices[k])}")
                here, k = vertices[k], k + 1
            elif code == MplPath.CURVE3:
                q, end = vertices[k], vertices[k + 1]
                d.append(f"C {f(here + 2 / 3 * (q - here), end + 2 / 3 * (q - end), end)}" if cubic else f"Q {f(q, end)}")
                here, k = end, k + 2
            elif code == MplPath.CURVE4:
                d.append(f"C {f(vertices[k], vertices[k + 1], vertices[k + 2])}")
                here, k = vertices[k + 2], k + 3
            else:  # CLOSEPOLY (or STOP)
                d.append("Z")
                k += 1
        paths.append(f'<path d="{" ".join(d)}" fill="none" stroke="black"/>')
    path = folder / f"{name}.svg"
    path.write_text('<svg xmlns="http://www.w3.org/2000/svg" width="700mm" height="200mm" viewBox="-10 -60 700 200">\n'
                    + "\n".join(paths) + "\n</svg>\n", encoding="utf-8")
    return path


def generated_text(folder: Path) -> list[Path]:
    """The text-outline drawings: the greeting at 30 and 6 mm, cubic and quadratic, in a sans and a
    serif face, with coordinates at 4 decimals and at 1 (as some exporters round them)."""
    return [text_outlines(folder, GREETING, "text_sans_30mm_cubic"),
            text_outlines(folder, GREETING, "text_sans_30mm_quadratic", cubic=False),
            text_outlines(folder, GREETING, "text_sans_6mm_cubic", height_mm=6.0),
            text_outlines(folder, GREETING, "text_sans_30mm_cubic_1_decimal", decimals=1),
            text_outlines(folder, GREETING, "text_serif_12mm_cubic", family="DejaVu Serif", height_mm=12.0)]


def drawings(paths: list[str]) -> list[Path]:
    found: list[Path] = []
    for item in paths:
        p = Path(item)
        if p.is_dir():
            found += sorted(q for q in p.rglob("*") if q.suffix.lower() in DRAWING_SUFFIXES)
        else:
            found.append(p)
    return found


class FitClock:
    """Counts the free-form fits the fitter makes and their CPU seconds (contour_fit.fit_run,
    wrapped: a stretch that copies one fitted before reuses its fit and is not counted)."""

    def __init__(self) -> None:
        self.fits, self.seconds = 0, 0.0
        original = contour_fit.fit_run

        def timed(*args, **kwargs):
            started = time.process_time()
            try:
                return original(*args, **kwargs)
            finally:
                self.fits += 1
                self.seconds += time.process_time() - started

        contour_fit.fit_run = timed


def measure(path: Path, tol: float, clock: FitClock) -> tuple[dict | None, float, str]:
    """(stats or None, CPU seconds, the table row)."""
    clock.fits, clock.seconds = 0, 0.0
    started = time.process_time()
    try:
        part = segment_drawing(path, tol)
    except CoatsimError as exc:
        return None, 0.0, f"| {path.name} | refused: {str(exc).replace(str(path), 'file')} | | | | | | | | |"
    seconds = time.process_time() - started
    st = part.stats()
    per_fit = f"{clock.seconds / clock.fits:.3f}" if clock.fits else "-"
    return st, seconds, (
        f"| {path.name} | {st['n_contours']} ({st['n_closed']} closed) | {st['input_primitives']} | {clock.fits} | "
        f"{st['n_segments']} ({st['n_arcs']} arcs, {st['n_lines']} lines) | {st['n_corners']} | "
        f"{st['max_deviation_mm']:.4g} | {st['max_tangent_break_deg']:.2g} | {seconds:.2f} | {per_fit} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("paths", nargs="*", help="folders or drawing files")
    parser.add_argument("--tol", type=float, default=0.1, help="tolerance sigma, mm")
    parser.add_argument("--no-generated", action="store_true", help="skip the generated drawings")
    args = parser.parse_args()
    clock = FitClock()
    print(f"tolerance {args.tol:g} mm, join tolerance {args.tol / 100:g} mm; CPU seconds\n")
    print("| drawing | contours | pieces in | free-form fits | segments out | corners | deviation mm | tangent break deg "
          "| seconds | seconds per fit |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in drawings(args.paths):
        print(measure(path, args.tol, clock)[2], flush=True)
    if args.no_generated:
        return
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        for path in (generated_native(folder), generated_mixed(folder), generated_splines(folder), *generated_text(folder)):
            print(measure(path, args.tol, clock)[2], flush=True)
        print("\n| exponent against size | pieces | seconds | pieces | seconds | exponent |\n|---|---|---|---|---|---|")
        short, long = (measure(text_outlines(folder, t, f"size_{k}"), args.tol, clock)[:2]
                       for k, t in enumerate((SHORT_GREETING, GREETING)))
        n1, n2 = short[0]["input_primitives"], long[0]["input_primitives"]
        print(f"| text outlines (sans, 30 mm, cubic) | {n1} | {short[1]:.2f} | {n2} | {long[1]:.2f} | "
              f"{math.log(long[1] / short[1]) / math.log(n2 / n1):.2f} |")


if __name__ == "__main__":
    main()
