"""String values of AS expressions: the $-functions ($MID, $LEFT, $RIGHT, $CHR, $SPACE,
$ENCODE, $DECODE), the number formats of $ENCODE and TYPE (/D, /Fw.d, /Ew.d, /Gw.d, /Xn) and
VAL's reading of a number at the start of a string."""

from __future__ import annotations

import math
from typing import Optional

from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.machine import Evaluation

_MAX_FIELD = 1000  # widths and digits of a number format (a controller's string holds 128 characters)

# $-functions of the index the twin does not compute (clock, errors, system data): "".
_NOT_SIMULATED = {"$DATE", "$TIME", "$ERROR", "$ERRORS", "$ERRLOG", "$SYSDATA"}


def val(text: str) -> float:
    """VAL: the longest number at the start of ``text`` (0 if none)."""
    text = text.strip()
    best = 0.0
    for end in range(len(text), 0, -1):
        try:
            best = float(text[:end])
            break
        except ValueError:
            continue
    return best if math.isfinite(best) else 0.0


def string_call(ev: Evaluation, e: ast.Call) -> str:
    """The value of a $-function call."""
    name = e.name
    if name == "$MID":
        text = ev.string(ev.arg(e, 0))
        start = ev.integer(ev.arg(e, 1), "$MID start")
        count = ev.integer(e.args[2], "$MID length") if len(e.args) > 2 and e.args[2] is not None else len(text)
        return text[max(start, 1) - 1:max(start, 1) - 1 + max(count, 0)]
    if name == "$LEFT":
        return ev.string(ev.arg(e, 0))[:max(ev.integer(ev.arg(e, 1), "$LEFT length"), 0)]
    if name == "$RIGHT":
        n = max(ev.integer(ev.arg(e, 1), "$RIGHT length"), 0)
        text = ev.string(ev.arg(e, 0))
        return text[len(text) - n:] if n else ""
    if name == "$CHR":
        code = ev.integer(ev.arg(e, 0), "$CHR code")
        if not 0 <= code <= 255:
            raise ev.error(f"$CHR code {code} out of range 0..255")
        return chr(code)
    if name == "$SPACE":
        return " " * min(max(ev.integer(ev.arg(e, 0), "$SPACE count"), 0), 10_000)
    if name == "$ENCODE":
        return encode(ev, e.args)
    if name == "$DECODE":
        return decode(ev, e)
    what = "is not simulated" if name in _NOT_SIMULATED else \
        "is not a function of the AS index coatsim knows (an array takes [ ], not ( ))"
    ev.run.not_simulated(f"function:{name}", f"{name} {what}; it gives an empty string")
    return ""


def encode(ev: Evaluation, items: tuple[Optional[ast.Expr], ...]) -> str:
    """$ENCODE / TYPE text: values in the current format (/D, /Fw.d, /Ew.d, /Gw.d, /Xn)."""
    out, fmt = [], "G"
    for item in items:
        if item is None:
            continue
        if isinstance(item, ast.Format):
            spec = item.spec
            if spec.startswith("X"):
                out.append(" " * min(int(spec[1:] or 1), 1000))
            elif spec[:1] in ("D", "F", "E", "G"):
                fmt = spec
            continue
        if ev.kind(item) == "string":
            out.append(ev.string(item))
            continue
        out.append(format_number(ev.real(item), fmt))
    return ev.joined(out)


def decode(ev: Evaluation, e: ast.Call) -> str:
    """$DECODE($s, $separators, mode): the leading characters of $s up to a separator
    (mode 0, the default) or the leading separators (mode 1), removed from $s (a string
    variable, written plain as cells do or as a reference ``&$s``)."""
    target = ev.arg(e, 0)
    if isinstance(target, ast.Ref):
        target = target.target
    if not isinstance(target, ast.Name) or target.kind != "string":
        raise ev.error("$DECODE takes a string variable first (it removes what it returns), as in "
                         "$DECODE($s, \",\", 0)")
    text = ev.run.get_string(target)
    seps = ev.string(ev.arg(e, 1))
    mode = ev.integer(ev.arg(e, 2), "the $DECODE mode") if len(e.args) > 2 else 0
    i = 0
    while i < len(text) and ((text[i] in seps) == (mode != 0)):
        i += 1
    ev.run.set_string(target, text[i:])
    return text[:i]


def format_number(x: float, fmt: str) -> str:
    """``x`` in the format ``fmt`` (D, Fw.d, Ew.d, Gw.d; w the width, d the digits)."""
    kind, spec = fmt[0], fmt[1:]
    width, _, digits = spec.partition(".")
    w = min(int(width), _MAX_FIELD) if width.isdigit() else 0
    d = min(int(digits), _MAX_FIELD) if digits.isdigit() else None
    if kind == "D":
        return f"{int(round(x)):{w}d}"
    if kind == "F":
        return f"{x:{w}.{3 if d is None else d}f}"
    if kind == "E":
        return f"{x:{w}.{3 if d is None else d}e}"
    return f"{x:{w}.{6 if d is None else d}g}"
