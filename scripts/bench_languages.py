"""Robot languages: parse+interpret speed of programs of N and 2N moves in every registered
language (CPU s, best of 3, and the exponent against N), and the lines of text and moves read back
of the shipped scenarios' curves' variants in each. Two programs per language where it has both:
one coatsim wrote (a zigzag polyline, blended) and one in a person's style whose poses a loop
computes (Fanuc FOR with position register arithmetic, URScript while with pose_add, G-code
incremental moves with parameters). Prints only; never asserts.

    python scripts/bench_languages.py [N [LANGUAGE ...]]   (default 5000 moves, every language;
    naming languages times only their reading)
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from scaling import cpu, exponent  # noqa: E402


def zigzag(n_moves: int):
    """A polyline of ``n_moves`` lines as a polysegment: a zigzag of 2 mm steps in rows of 500
    (1 m wide, 20 mm apart), so that any size stays within every language's coordinates."""
    import numpy as np

    from coatsim.path.placement import polyline_polysegment

    k = np.arange(n_moves + 1)
    row, col = k // ROW_MOVES, k % ROW_MOVES
    x = np.where(row % 2 == 0, col, ROW_MOVES - col) * 2.0
    y = row * 20.0 + (k % 2)
    return polyline_polysegment(np.column_stack((x - x.mean(), y - y.mean())), False)


ROW_MOVES = 500


LOOPED = ("fanuc-tp", "urscript", "gcode")


def looped(name: str, n: int) -> str:
    """A program of ``n`` moves whose targets a loop computes, in a person's style."""
    if name == "fanuc-tp":
        return ("/PROG  LOOPED\n/MN\n   1:  UFRAME_NUM=0 ;\n   2:  UTOOL_NUM=0 ;\n   3:J P[1] 50% FINE ;\n"
                "   4:  PR[1]=LPOS ;\n   5:  PR[2,1]=0 ;\n   6:  PR[2,2]=0.1 ;\n"
                f"   7:  FOR R[1]=1 TO {n - 1} ;\n   8:  PR[1]=PR[1]+PR[2] ;\n   9:  R[2]=R[1] MOD 2 ;\n"
                "  10:  IF R[2]=0,JMP LBL[1] ;\n  11:L PR[1] 200mm/sec CNT50 ;\n  12:  JMP LBL[2] ;\n"
                "  13:  LBL[1] ;\n  14:L PR[1] 250mm/sec CNT50 ;\n  15:  LBL[2] ;\n  16:  ENDFOR ;\n/POS\n"
                "P[1]{GP1: UF : 0, UT : 0, X = 700 mm, Y = -200 mm, Z = 300 mm, W = 180 deg, P = 0 deg, "
                "R = 0 deg};\n/END\n")
    if name == "urscript":
        return ("def looped():\n  start = p[0.7, -0.2, 0.3, 3.14159265359, 0, 0]\n  movej(start)\n  i = 1\n"
                f"  while (i < {n}):\n    target = pose_add(start, p[0, 0.0001 * i, 0, 0, 0, 0])\n"
                "    if (i % 2 == 0):\n      movel(target, v=0.2, r=0.00005)\n    else:\n"
                "      movel(target, v=0.25, r=0.00005)\n    end\n    i = i + 1\n  end\nend\n")
    return ("G21 G90 G64 P0.05\nG0 X700 Y-200 Z300\nG91\n#1 = 0\n"
            + "".join(f"G1 Y[0.1 + #1 * 0] F{12000 + 3000 * (k % 2)}\n#1 = [#1 + 1]\n" for k in range(n - 1)))


def read_speed(n: int, only: tuple[str, ...] = ()) -> None:
    """Each language reads a program of ``n`` and one of ``2 n`` moves: one plan per size (the plan
    is language-neutral), written in each language, and the looped programs of a person's style."""
    from dataclasses import replace

    from coatsim.languages.registry import DEFAULT_LANGUAGE, LANGUAGES
    from coatsim.path.build import ProgramOptions
    from coatsim.path.language import ReadOptions
    from coatsim.path.part_program import build_part_program
    from coatsim.path.placement import Placement
    from coatsim.path.program_files import program_suffixes, write_program

    plans = {size: build_part_program([zigzag(size)], Placement(lead_in_mm=10.0, lead_out_mm=10.0),
                                      ProgramOptions(variant="polyline-blend"), tolerance_mm=0.1, source="bench",
                                      language=LANGUAGES[DEFAULT_LANGUAGE]).plan for size in (n, 2 * n)}
    print(f"# parse + interpret (CPU s, best of 3): programs of ~{n} and ~{2 * n} moves")
    print(f"  {'language':<12} {'program':<8} {'moves':>7} {'lines':>7} {'t1 s':>7} {'moves':>7} {'t2 s':>7} "
          f"{'moves/s':>9} {'exponent':>9}")
    with tempfile.TemporaryDirectory() as folder:
        for name, lang in LANGUAGES.items():
            if only and name not in only:
                continue
            for kind in ("written", "looped") if name in LOOPED else ("written",):
                row = []
                for size in (n, 2 * n):
                    text = lang.write(replace(plans[size], name=lang.program_name("bench"))) if kind == "written" \
                        else looped(name, size)
                    paths = write_program(lang, text, Path(folder) / f"b{size}{program_suffixes(lang)[0]}")
                    t, toolpath = cpu(lambda: lang.read(list(paths), ReadOptions()), repeat=3)
                    row.append((len(toolpath.moves), text.count("\n"), t))
                (m1, l1, t1), (m2, _, t2) = row
                print(f"  {name:<12} {kind:<8} {m1:>7} {l1:>7} {t1:>7.3f} {m2:>7} {t2:>7.3f} {m2 / t2:>9.0f} "
                      f"{exponent(m1, t1, m2, t2):>9.2f}", flush=True)


def scenario_sizes() -> None:
    """Lines of text / moves read back of each shipped scenario's program, per variant and language."""
    from dataclasses import replace

    from coatsim.core.errors import CoatsimError
    from coatsim.languages.registry import DEFAULT_LANGUAGE, LANGUAGES, language
    from coatsim.path.build import ProgramOptions, polyline_of
    from coatsim.path.language import ReadOptions
    from coatsim.path.part_program import build_part_program
    from coatsim.path.placement import Placement
    from coatsim.path.program_files import program_suffixes, write_program
    from coatsim.run.scenario import load_scenario
    from coatsim.run.scenario_inputs import curve_frame, load_arm, segment_input

    names = tuple(LANGUAGES)
    root = Path(__file__).resolve().parents[1] / "scenarios"
    print("\n# shipped scenarios: lines of text / moves read back")
    print(f"  {'scenario':<20} {'variant':<15} " + " ".join(f"{n:>13}" for n in names))
    for path in sorted(root.glob("*.yaml")):
        loaded = load_scenario(path)
        spec = loaded.spec
        if spec.curve is None:
            print(f"  {path.stem:<20} (a user's program: no curve to write)")
            continue
        contours, _ = segment_input(loaded, load_arm(loaded, None))
        polylines = [polyline_of(c.curve.points, c.polysegment.closed, spec.segmentation.tolerance_mm) for c in contours]
        place = Placement(frame=curve_frame(spec), standoff_mm=spec.gun.standoff_mm, lead_in_mm=spec.motion.lead_in_mm,
                          lead_out_mm=spec.motion.lead_out_mm, offset_xy=(0.0, 0.0))
        for variant in ("polysegment", "polyline-stop", "polyline-blend"):
            options = ProgramOptions(variant=variant, speed_mm_s=spec.motion.speed_mm_s,
                                     accuracy_mm=spec.motion.accuracy_mm)
            plan = build_part_program([c.polysegment for c in contours], place, options,
                                      tolerance_mm=spec.segmentation.tolerance_mm, source=path.stem,
                                      language=language(DEFAULT_LANGUAGE), points=[c.curve.points for c in contours],
                                      polylines=polylines).plan  # language-neutral: written in each below
            cells = []
            for name in names:
                lang = language(name)
                try:
                    text = lang.write(replace(plan, name=lang.program_name(plan.name)))
                    with tempfile.TemporaryDirectory() as folder:
                        files = write_program(lang, text, Path(folder) / f"p{program_suffixes(lang)[0]}")
                        moves = len(lang.read(list(files), ReadOptions()).moves)
                    cells.append(f"{text.count(chr(10))}/{moves}")
                except CoatsimError as exc:
                    cells.append("refused" if "tool orientation" in str(exc) else type(exc).__name__)
            print(f"  {path.stem:<20} {variant:<15} " + " ".join(f"{c:>13}" for c in cells), flush=True)


if __name__ == "__main__":
    read_speed(int(sys.argv[1]) if len(sys.argv) > 1 else 5000, tuple(sys.argv[2:]))
    if len(sys.argv) <= 2:
        scenario_sizes()
