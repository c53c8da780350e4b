"""One AS program written the ways different authors write it: a controller backup (``.*``
header, controller sections, ``#0`` after the header, CRLF), a K-IDE project (lower case, tabs,
comments), step numbers on every line, mixed case, and plain upper case. The meaning never
changes: keywords and names are case-insensitive, strings are kept as written."""

from __future__ import annotations

import re

from coatsim.languages.kawasaki_as import interpret_run, parse_as

STYLES = ("backup", "kide", "numbered", "mixed", "upper")
_STRING = re.compile(r'("[^"]*")')


def _outside_strings(text: str, change) -> str:
    return "".join(part if part.startswith('"') else change(part) for part in _STRING.split(text))


def _title(part: str) -> str:
    return re.sub(r"[A-Za-z_][A-Za-z0-9_.]*", lambda m: m.group()[:1].upper() + m.group()[1:].lower(), part)


def styled(body: str, style: str, data: str = "", name: str = "main", extra: str = "") -> str:
    """The program ``name`` with ``body`` (statements, one a line, upper case) and the
    programs ``extra`` and data sections ``data`` after it, in ``style``."""
    lines = [line.strip() for line in body.strip("\n").split("\n")]
    if style == "backup":
        head = [".***************************************************************", ".*USER IF AS : UAS 2020/01/01",
                '.NETCONF     192.168.0.2,"CELL",255.255.255.0', ".AUXDATA", "TOOL1 0.0 0.0 250.0 0.0 0.0 0.0",
                ".END", f".PROGRAM {name}() #0"]
        text = "\r\n".join(head + [f"  {line}" for line in lines] + [".END"]) + "\r\n"
        return text + (extra + data).replace("\r\n", "\n").replace("\n", "\r\n")
    if style == "kide":
        out = [f".PROGRAM {name}() ; written in K-IDE"]
        out += [f"\t{line}" + ("\t; step" if i % 3 == 0 else "") for i, line in enumerate(lines)]
        text = "\n".join(out + [".END"]) + "\n" + extra + data
        return _outside_strings(text, str.lower)
    if style == "numbered":
        out = [f".PROGRAM {name}()"] + [f" {10 * (i + 1)} {line}" for i, line in enumerate(lines)]
        return "\n".join(out + [".END"]) + "\n" + extra + data
    text = "\n".join([f".PROGRAM {name}()"] + [f"  {line}" for line in lines] + [".END"]) + "\n" + extra + data
    return _outside_strings(text, _title) if style == "mixed" else text


def run_text(text: str, **options):
    """Parse and interpret ``text`` (source name f.as) without a cell model; the Run."""
    return interpret_run(parse_as(text, "f.as"), **options)


def notes(run) -> str:
    return "\n".join(run.toolpath.warnings)


def ends(run) -> list:
    """The end position (mm) of every move of a run."""
    return [getattr(m, "end", None) or m.target for m in run.toolpath.moves]


def ys(run) -> list[int]:
    """The end y (mm, rounded) of every move of a run."""
    return [round(float(p.translation_mm[1])) for p in ends(run)]
