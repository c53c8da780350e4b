"""Run hostile inputs against the ``coatsim`` command and print what became of each.

Every case (scripts/hostile_cases.py) runs in a fresh process with a memory cap (RLIMIT_AS) and a
timeout, in a folder of its own. Each outcome is sorted into one class:

  ok            exit 0, stderr clean (warnings are one line each)
  clean error   exit 1, 2 or 3 with one line on stderr naming what is wrong
  messy error   exit 1, 2 or 3 but stderr is not one clean line (a RuntimeWarning, a line over
                1000 characters, a second line)
  internal      exit 70, a traceback, a signal or any other exit code
  wrong         the case's own check says the result is silently wrong
  data loss     the case's own check says a file coatsim did not create was changed
  hang          still running at the timeout (killed)

A *bomb* (a small input asking for huge work) must be refused: the table lists its seconds and
peak memory, and counts the bombs that were not refused within 10 s and 1 GB.

    python scripts/hostile.py                         # all cases against this checkout
    python scripts/hostile.py --root /tmp/base -j 2   # against another source tree
    python scripts/hostile.py --only dxf --json after.json --compare before.json
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from hostile_cases import Case, Outcome, all_cases  # noqa: E402

CLASSES = ("ok", "clean error", "messy error", "internal", "wrong", "data loss", "hang")
BOMB_SECONDS, BOMB_MB = 10.0, 1000.0


@dataclass
class Result:
    category: str
    name: str
    cls: str
    code: int | None
    seconds: float
    peak_mb: float
    bomb: bool
    detail: str


def _limit(cap_bytes: int):
    def apply() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (cap_bytes, cap_bytes))
        resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    return apply


def run_case(case: Case, root: Path, work: Path, cap_gb: float, timeout: float) -> Result:
    folder = work / f"{case.category}-{case.name}".replace("/", "_")
    folder.mkdir(parents=True)
    try:
        if case.setup is not None:
            case.setup(folder)
    except Exception as exc:  # a broken case, not a finding
        return Result(case.category, case.name, "setup failed", None, 0.0, 0.0, case.bomb, repr(exc)[:200])
    argv = [sys.executable, "-m", "coatsim.cli", *(a.replace("{d}", str(folder)) for a in case.argv)]
    env = {**os.environ, "PYTHONPATH": str(root), "MPLBACKEND": "Agg", "OMP_NUM_THREADS": "1",
           "OPENBLAS_NUM_THREADS": "1", "COLUMNS": "200"}
    env.pop("COATSIM_TRACEBACK", None)
    out_path = Path(case.stdout) if case.stdout else folder / ".stdout"
    started = time.perf_counter()
    with open(out_path, "wb") as out, open(folder / ".stderr", "wb") as err:
        proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=out, stderr=err, cwd=folder, env=env,
                                preexec_fn=_limit(int(cap_gb * (1 << 30))), start_new_session=True)
        limit = case.timeout or timeout
        status, usage, timed_out = None, None, False
        while status is None:
            pid, st, ru = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                status, usage = st, ru
                break
            if time.perf_counter() - started > limit:
                timed_out = True
                os.killpg(proc.pid, signal.SIGKILL)
                _, status, usage = os.wait4(proc.pid, 0)
                break
            time.sleep(0.05)
        proc.returncode = os.waitstatus_to_exitcode(status)
    seconds = time.perf_counter() - started
    try:
        os.killpg(proc.pid, signal.SIGKILL)  # leftovers (a local Dask cluster's workers)
    except ProcessLookupError:
        pass
    stdout = b"" if case.stdout else (folder / ".stdout").read_bytes()[:1 << 20]
    stderr = (folder / ".stderr").read_bytes()[:1 << 22].decode("utf-8", "replace")
    outcome = Outcome(proc.returncode, stdout.decode("utf-8", "replace"), stderr, seconds, timed_out)
    cls, detail = classify(case, folder, outcome)
    peak = usage.ru_maxrss / 1024.0 if usage else 0.0
    _unfreeze(folder)
    return Result(case.category, case.name, cls, proc.returncode, round(seconds, 2), round(peak, 1), case.bomb,
                  detail)


def classify(case: Case, folder: Path, o: Outcome) -> tuple[str, str]:
    first = (o.stderr.strip().splitlines() or [""])[-1][:300]
    if o.timed_out:
        return "hang", f"killed after {o.seconds:.0f} s"
    if case.check is not None:
        try:
            problem = case.check(folder, o)
        except Exception as exc:  # the check itself could not look: report it
            problem = f"wrong: check failed ({exc!r})"[:300]
        if problem:
            return ("data loss" if problem.startswith("data loss") else "wrong"), problem[:300]
    if o.code == 70 or "Traceback (most recent call last)" in o.stderr or o.code not in (0, 1, 2, 3):
        return "internal", f"exit {o.code}: {first}"
    lines = o.stderr.splitlines()
    bad = [ln for ln in lines if not ln.startswith(("coatsim: ", "warning: ")) or len(ln) > 1000]
    errors = [ln for ln in lines if ln.startswith("coatsim: error")]
    if o.code == 0:  # a command may print its summary on stderr; stray warnings and huge lines are not clean
        noisy = [ln for ln in lines if "Warning: " in ln or len(ln) > 1000]
        return ("messy error", f"exit 0 with stderr: {noisy[0][:200]}") if noisy else ("ok", "")
    if bad or len(errors) != 1:
        why = f"{len(lines)} lines, longest {max(map(len, lines), default=0)}" if lines else "nothing on stderr"
        return "messy error", f"exit {o.code}: {why}: {(bad or lines or [''])[0][:200]}"
    return "clean error", f"exit {o.code}: {errors[0][:200]}"


def _unfreeze(folder: Path) -> None:
    """Undo the immutable flag some cases set on a folder (so it can be removed)."""
    for path in [folder, *folder.rglob("*")]:
        if path.is_dir() and not path.is_symlink():
            subprocess.run(["chattr", "-i", str(path)], capture_output=True)


def table(results: list[Result]) -> str:
    cats = sorted({r.category for r in results})
    head = f"{'category':<12}{'cases':>6}" + "".join(f"{c:>13}" for c in CLASSES) + f"{'peak MB':>9}"
    lines = [head, "-" * len(head)]
    for cat in cats + ["all"]:
        rs = [r for r in results if cat in ("all", r.category)]
        counts = [sum(r.cls == c for r in rs) for c in CLASSES]
        peak = max((r.peak_mb for r in rs), default=0.0)
        lines.append(f"{cat:<12}{len(rs):>6}" + "".join(f"{n:>13}" for n in counts) + f"{peak:>9.0f}")
    bombs = [r for r in results if r.bomb]
    if bombs:
        slow = [r for r in bombs if r.cls != "clean error" or r.seconds > BOMB_SECONDS or r.peak_mb > BOMB_MB]
        lines += ["", f"bombs: {len(bombs)}, not refused within {BOMB_SECONDS:g} s and {BOMB_MB:g} MB: {len(slow)}",
                  f"{'bomb':<44}{'class':>14}{'s':>8}{'MB':>8}"]
        lines += [f"{r.category + '/' + r.name:<44}{r.cls:>14}{r.seconds:>8.1f}{r.peak_mb:>8.0f}" for r in bombs]
    setup = [r for r in results if r.cls == "setup failed"]
    if setup:
        lines += ["", f"{len(setup)} case(s) could not be set up: " + "; ".join(f"{r.name}: {r.detail}" for r in setup)]
    return "\n".join(lines)


def findings(results: list[Result]) -> str:
    bad = [r for r in results if r.cls not in ("ok", "clean error") or (r.bomb and r.seconds > BOMB_SECONDS)]
    return "\n".join(f"{r.cls:>12}  {r.category}/{r.name} ({r.seconds:.1f} s, {r.peak_mb:.0f} MB): {r.detail}"
                     for r in bad)


def compare(before: list[dict], after: list[Result]) -> str:
    old = {(r["category"], r["name"]): r for r in before}
    rows = []
    for r in after:
        b = old.get((r.category, r.name))
        if b is not None and b["cls"] != r.cls:
            rows.append(f"{r.category}/{r.name}: {b['cls']} -> {r.cls}")
    return "\n".join(rows)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", type=Path, default=Path(__file__).resolve().parents[1], help="source tree to run")
    parser.add_argument("--only", action="append", help="category or category/name prefix (repeatable)")
    parser.add_argument("--cases", type=Path, help="a file of category/name lines: run exactly these cases")
    parser.add_argument("-j", "--jobs", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=60.0, help="seconds per case")
    parser.add_argument("--mem-gb", type=float, default=3.0, help="address-space cap per case")
    parser.add_argument("--json", type=Path, help="write every result here")
    parser.add_argument("--compare", type=Path, help="a --json file of an earlier run: list what changed")
    parser.add_argument("--findings", action="store_true", help="list every case that is not ok or a clean error")
    args = parser.parse_args()
    chosen = set(args.cases.read_text().splitlines()) if args.cases else None
    cases = [c for c in all_cases() if (not args.only or any(f"{c.category}/{c.name}".startswith(o) for o in args.only))
             and (chosen is None or f"{c.category}/{c.name}" in chosen)]
    work = Path(tempfile.mkdtemp(prefix="coatsim-hostile-"))
    print(f"{len(cases)} cases, {args.jobs} at a time, {args.timeout:g} s and {args.mem_gb:g} GB each, in {work}",
          file=sys.stderr)
    done = 0

    def one(case: Case) -> Result:
        nonlocal done
        result = run_case(case, args.root, work, args.mem_gb, args.timeout)
        done += 1
        print(f"[{done}/{len(cases)}] {result.cls:>12} {result.seconds:6.1f} s  {case.category}/{case.name}",
              file=sys.stderr, flush=True)
        return result

    try:
        with ThreadPoolExecutor(args.jobs) as pool:
            results = list(pool.map(one, cases))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(table(results))
    if args.findings:
        print("\n" + findings(results))
    if args.compare:
        print("\nchanged:\n" + compare(json.loads(args.compare.read_text()), results))
    if args.json:
        args.json.write_text(json.dumps([asdict(r) for r in results], indent=1))


if __name__ == "__main__":
    main()
