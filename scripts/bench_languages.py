"""Robot languages: parse+interpret speed of a program of N and 2N moves in every registered
language (CPU s, exponent), and the lines of text and moves of the shipped scenarios' curves'
polysegment and polyline variants in each. Prints only; never asserts.

    python scripts/bench_languages.py [N]   (default 5000 moves)
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from scaling import cpu, exponent  # noqa: E402


def zigzag(n_moves: int):
    """A polyline of ``n_moves`` lines (a zigzag, 2 mm steps) as a polysegment."""
    import numpy as np

    from coatsim.path.placement import polyline_polysegment

    x = np.arange(n_moves + 1) * 2.0
    y = np.where(np.arange(n_moves + 1) % 2 == 0, 0.0, 1.0)
    return polyline_polysegment(np.column_stack((x - x.mean(), y)), False)


def program_of(lang, poly, variant: str = "polyline-blend"):
    from coatsim.path.build import ProgramOptions
    from coatsim.path.part_program import build_part_program
    from coatsim.path.placement import Placement

    return build_part_program([poly], Placement(lead_in_mm=10.0, lead_out_mm=10.0), ProgramOptions(variant=variant),
                              tolerance_mm=0.1, source="bench", language=lang)


def read_speed(n: int) -> None:
    from coatsim.languages.registry import LANGUAGES
    from coatsim.path.language import ReadOptions
    from coatsim.path.program_files import program_suffixes, write_program

    print(f"# parse + interpret (CPU s, best of 3): programs of ~{n} and ~{2 * n} moves")
    print(f"  {'language':<14} {'moves':>7} {'lines':>7} {'t1':>8} {'moves':>7} {'t2':>8} {'exponent':>9}")
    for name, lang in LANGUAGES.items():
        row = []
        with tempfile.TemporaryDirectory() as folder:
            for size in (n, 2 * n):
                built = program_of(lang, zigzag(size))
                paths = write_program(lang, built.text, Path(folder) / f"b{size}{program_suffixes(lang)[0]}")
                t, toolpath = cpu(lambda: lang.read(list(paths), ReadOptions()), repeat=3)
                row.append((len(toolpath.moves), built.text.count("\n"), t))
        (m1, l1, t1), (m2, _, t2) = row
        print(f"  {name:<14} {m1:>7} {l1:>7} {t1:>8.3f} {m2:>7} {t2:>8.3f} {exponent(m1, t1, m2, t2):>9.2f}")


def scenario_sizes() -> None:
    from coatsim.languages.registry import LANGUAGES
    from coatsim.path.language import ReadOptions
    from coatsim.path.program_files import program_suffixes, write_program
    from coatsim.run.scenario import load_scenario
    from coatsim.run.scenario_inputs import segment_input, load_arm

    root = Path(__file__).resolve().parents[1] / "scenarios"
    print("\n# shipped scenarios: lines of text / moves read back, per language and variant")
    print(f"  {'scenario':<20} {'variant':<15} " + " ".join(f"{n:>16}" for n in LANGUAGES))
    for path in sorted(root.glob("*.yaml")):
        loaded = load_scenario(path)
        if loaded.spec.curve is None:
            continue
        try:
            contours, _ = segment_input(loaded, load_arm(loaded, None))
        except Exception as exc:  # a scenario needing more than a curve: say so, go on
            print(f"  {path.stem:<20} skipped ({type(exc).__name__})")
            continue
        for variant in ("polysegment", "polyline-blend"):
            cells = []
            for lang in LANGUAGES.values():
                from coatsim.path.build import ProgramOptions
                from coatsim.path.part_program import build_part_program
                from coatsim.path.placement import Placement

                built = build_part_program([c.polysegment for c in contours], Placement(),
                                           ProgramOptions(variant=variant), tolerance_mm=loaded.spec.segmentation.tolerance_mm,
                                           source=path.stem, language=lang,
                                           points=[c.curve.points for c in contours])
                with tempfile.TemporaryDirectory() as folder:
                    files = write_program(lang, built.text, Path(folder) / f"p{program_suffixes(lang)[0]}")
                    moves = len(lang.read(list(files), ReadOptions()).moves)
                cells.append(f"{built.text.count(chr(10))}/{moves}")
            print(f"  {path.stem:<20} {variant:<15} " + " ".join(f"{c:>16}" for c in cells))


if __name__ == "__main__":
    read_speed(int(sys.argv[1]) if len(sys.argv) > 1 else 5000)
    scenario_sizes()
