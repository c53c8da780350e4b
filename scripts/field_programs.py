"""Read / partly / refused: ``coatsim check-program`` on programs written in field styles.

Runs the check on every program of a folder (default: tests/languages/kawasaki_as/data/field)
with the shipped cell, each file in the language its suffix or opening names (a KRL ``.dat`` is
read with its ``.src``), and prints one line per program and a count per style: for AS the file
name's first letter (b controller backup, k K-IDE project, m mixed case, n step numbers, u upper
case), for the other languages the language (tests/languages/data/held_out: programs in RAPID,
KRL, Fanuc TP, URScript and G-code; the values their controllers keep are not given, so a
program that needs one reads *partly*).
A program is *read* when the check ends with exit 0 and skipped nothing, *partly* when it ends
with exit 0 but skipped statements (a motion to a pose no file gives, a program CALLed but not
loaded, a motion the twin does not simulate), *refused* when it ends with an error (or an
internal error). Never asserts.

    python scripts/field_programs.py [DIR]
"""

from __future__ import annotations

import sys
from collections import Counter
from pathlib import Path

from coatsim.core.errors import CoatsimError

STYLES = {"b": "backup", "k": "K-IDE", "m": "mixed case", "n": "step numbers", "u": "upper case"}


def classify(path: Path, kinematics, gun_tcp) -> tuple[str, str]:
    from coatsim.languages.registry import language_of
    from coatsim.path.check import check_program
    from coatsim.path.language import ReadOptions

    try:
        done = check_program(path, language_of([path]), ReadOptions(kinematics=kinematics), gun_tcp=gun_tcp)
    except CoatsimError as exc:
        return "refused", str(exc).splitlines()[0][:150]
    except Exception as exc:  # what the command reports as an internal error (exit 70)
        return "refused", f"internal error: {type(exc).__name__}"
    if getattr(done, "errors", ()):  # (the check before: a gun that never opens was an error)
        return "refused", done.errors[0][:150]
    skipped = tuple(getattr(done, "skipped", ()))
    if skipped:
        return "partly", skipped[0][:150]
    return "read", f"{len(done.toolpath.moves)} moves, {len(getattr(done, 'unknowns', ()))} unknowns"


def _language(path: Path) -> str:
    from coatsim.languages.registry import language_of

    try:
        return language_of([path]).name
    except CoatsimError:
        return "unknown"


def main() -> None:
    from coatsim.robot.cell import load_cell
    from coatsim.robot.kinematics import CellKinematics

    folder = Path(sys.argv[1]) if len(sys.argv) > 1 else \
        Path(__file__).resolve().parents[1] / "tests" / "languages" / "kawasaki_as" / "data" / "field"
    files = sorted(p for p in folder.iterdir() if p.is_file() and p.suffix.lower() != ".dat")
    if not files:
        sys.exit(f"field_programs: no program files in {folder}")
    cell = load_cell()
    kinematics, gun_tcp = CellKinematics(cell), (cell.gun_rotation, cell.gun_offset_mm)
    counts: Counter = Counter()
    for path in files:
        verdict, detail = classify(path, kinematics, gun_tcp)
        style = STYLES.get(path.name[:1], "other") if path.suffix.lower() in (".as", ".pg") else _language(path)
        counts[(style, verdict)] += 1
        print(f"{path.name:26} {style:13} {verdict:8} {detail}")
    print(f"\n{'style':13} {'read':>5} {'partly':>7} {'refused':>8}")
    for style in sorted({s for s, _ in counts}):
        print(f"{style:13} {counts[(style, 'read')]:5d} {counts[(style, 'partly')]:7d} {counts[(style, 'refused')]:8d}")
    total = Counter(v for (_, v), n in counts.items() for _ in range(n))
    print(f"{'all':13} {total['read']:5d} {total['partly']:7d} {total['refused']:8d}")


if __name__ == "__main__":
    main()
