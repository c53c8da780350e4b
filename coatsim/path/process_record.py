"""The process record of a coatsim program as ``key=value`` fields, and as comment lines.

Every language carries the record in the comments it allows, one line per field: AS
``; coatsim: key=value``, RAPID ``! coatsim: key=value``, KRL ``;coatsim: key=value``, Fanuc TP
``! coatsim: ...``, URScript ``# coatsim: ...``, G-code ``(coatsim: ...)``. :func:`encode` and
:func:`decode` are the fields; :func:`comment_lines` and :func:`read_comment_lines` the comment
texts, where a language that limits the length of a comment (Fanuc's 32 characters) continues a
long field on further lines, ``coatsim+ rest`` (after one space) or ``coatsim& rest`` (directly).

One line per field, in a fixed order; a field the record does not hold is not written. A program
of several contours holds its per-contour fields (``closed``, ``sprayed``, ``speed_limits``) as one
value per contour in spray order, joined by `` | ``; a single value holds for every contour.
Speed limits are ``S0:S1:V`` items (mm along the curve proper, mm/s; ``S:S:0`` a true corner), or
``none``. Unknown keys are ignored (a person may add their own); a known key with a value that
is not of its kind is an InputError naming the program and the field.
"""

from __future__ import annotations

import math
from typing import Callable, Iterable, Optional, Sequence

from coatsim.core.errors import InputError
from coatsim.core.numbers import fmt_short
from coatsim.geometry.space.xyzoat import format_xyzoat, parse_xyzoat
from coatsim.path.process import SPEED_ON, ProcessInfo, SprayedContour
from coatsim.path.speed_limits import SpeedLimit

SPRAYED_CURVE = "curve"
SPRAYED_WITH_LEADS = "lead-in,curve,lead-out"
PART_SEPARATOR = " | "
SPEED_LIMITS_KEY = "speed_limits"
_NONE = "none"


def format_limits(limits: Sequence[SpeedLimit]) -> str:
    """A ``speed_limits`` value (mm and mm/s with 4 decimals)."""
    if not limits:
        return _NONE
    return " ".join(f"{lim.s0_mm:.4f}:{lim.s1_mm:.4f}:{lim.v_max_mm_s:.4f}" for lim in limits)


def parse_limits(text: str, where: str) -> tuple[SpeedLimit, ...]:
    """Read a ``speed_limits`` value; InputError naming ``where`` on anything else."""
    text = text.strip()
    if text == _NONE:
        return ()
    limits = []
    for item in text.split():
        parts = item.split(":")
        try:
            values = [float(p) for p in parts]
        except ValueError:
            values = []
        if len(values) != 3:
            raise InputError(f"{where}: header field {SPEED_LIMITS_KEY}: {item!r} is not S0:S1:V (mm, mm, mm/s)")
        try:
            limits.append(SpeedLimit(*values))
        except InputError as exc:
            raise InputError(f"{where}: header field {SPEED_LIMITS_KEY}: {exc}") from None
    if not limits:
        raise InputError(f"{where}: header field {SPEED_LIMITS_KEY} is empty; write '{_NONE}' for no limit")
    return tuple(limits)


def _per_contour(values: Iterable[str]) -> str:
    return PART_SEPARATOR.join(values)


def encode(info: ProcessInfo) -> tuple[tuple[str, str], ...]:
    """The header fields of ``info``, in the order the writer emits them."""
    contours = info.contours
    fields: list[tuple[str, str | None]] = [
        ("variant", info.variant),
        ("source", info.source),
        ("tolerance_mm", None if info.tolerance_mm is None else fmt_short(info.tolerance_mm)),
        ("curve_length_mm", None if info.curve_length_mm is None else fmt_short(info.curve_length_mm)),
        ("lead_in_mm", fmt_short(info.lead_in_mm)),
        ("lead_out_mm", fmt_short(info.lead_out_mm)),
        ("standoff_mm", None if info.standoff_mm is None else fmt_short(info.standoff_mm)),
        ("speed_mm_s", None if info.speed_mm_s is None else fmt_short(info.speed_mm_s)),
        ("accuracy_mm", None if info.accuracy_mm is None else fmt_short(info.accuracy_mm)),
        ("gun_signal", None if info.gun_signal is None else str(info.gun_signal)),
        ("frame", None if info.frame is None else format_xyzoat(info.frame)),
        ("closed", _per_contour("yes" if c.closed else "no" for c in contours) if contours else None),
        ("sprayed", _per_contour(SPRAYED_WITH_LEADS if c.leads_sprayed else SPRAYED_CURVE for c in contours)
         if contours else None),
        ("n_segments", None if info.n_segments is None else str(info.n_segments)),
        ("n_lines", None if info.n_lines is None else str(info.n_lines)),
        ("n_arcs", None if info.n_arcs is None else str(info.n_arcs)),
        (SPEED_LIMITS_KEY, _per_contour(format_limits(c.speed_limits) for c in contours) if contours else None),
    ]
    if info.speed_on is not None:
        fields.append(("speed_on", info.speed_on))
    if info.contour_order is not None:
        fields += [("n_contours", str(len(info.contour_order))),
                   ("contour_order", ",".join(str(k) for k in info.contour_order))]
    return tuple((key, value) for key, value in fields if value is not None)


def _length(where: str, key: str, raw: str) -> float:
    """A length in mm (>= 0)."""
    try:
        value = float(raw)
    except ValueError:
        raise InputError(f"{where}: header field {key}={raw!r} is not a number (mm)") from None
    if not (math.isfinite(value) and value >= 0):
        raise InputError(f"{where}: header field {key}={raw!r} must be a length >= 0 mm")
    return value


def _count(where: str, key: str, raw: str) -> int:
    if not raw.strip().isdigit():
        raise InputError(f"{where}: header field {key}={raw!r} is not a whole number >= 0")
    return int(raw)


def _split(raw: str) -> list[str]:
    return [v.strip() for v in raw.split(PART_SEPARATOR.strip())]


def _closed(where: str, raw: str) -> bool:
    if raw not in ("yes", "no"):
        raise InputError(f"{where}: header field closed={raw!r}: expected 'yes' or 'no'")
    return raw == "yes"


def _sprayed(where: str, raw: str) -> bool:
    if raw not in (SPRAYED_CURVE, SPRAYED_WITH_LEADS):
        raise InputError(f"{where}: header field sprayed={raw!r}: expected {SPRAYED_CURVE!r} or {SPRAYED_WITH_LEADS!r}")
    return raw == SPRAYED_WITH_LEADS


def _contours(where: str, fields: dict[str, str]) -> tuple[SprayedContour, ...]:
    """One entry per contour from the per-contour fields (each a single value or one per contour)."""
    parsers: dict[str, Callable[[str], object]] = {
        "closed": lambda v: _closed(where, v),
        "sprayed": lambda v: _sprayed(where, v),
        SPEED_LIMITS_KEY: lambda v: parse_limits(v, where),
    }
    values = {key: [parse(v) for v in _split(fields[key])] for key, parse in parsers.items() if key in fields}
    if not values:
        return ()
    n = max(len(v) for v in values.values())
    for key, items in values.items():
        if len(items) not in (1, n):
            raise InputError(f"{where}: header field {key} holds {len(items)} values for {n} sprayed contours")
    each = {key: items * n if len(items) == 1 else items for key, items in values.items()}
    default = SprayedContour()
    return tuple(SprayedContour(closed=each["closed"][k] if "closed" in each else default.closed,
                                leads_sprayed=each["sprayed"][k] if "sprayed" in each else default.leads_sprayed,
                                speed_limits=each[SPEED_LIMITS_KEY][k] if SPEED_LIMITS_KEY in each else ())
                 for k in range(n))


def decode(pairs: Sequence[tuple[str, str]], where: str) -> ProcessInfo:
    """The process record of a program's header fields (the last of a repeated key counts)."""
    fields = dict(pairs)
    get = fields.get

    def optional(key: str, read: Callable[[str, str, str], float | int]) -> float | int | None:
        return None if key not in fields else read(where, key, fields[key])

    order = get("contour_order")
    if order is not None:
        try:
            contour_order = tuple(int(k) for k in order.split(","))
        except ValueError:
            raise InputError(f"{where}: header field contour_order={order!r} is not a list of contour numbers") from None
    else:
        contour_order = None
    return ProcessInfo(
        variant=get("variant"),
        source=get("source"),
        tolerance_mm=optional("tolerance_mm", _length),
        curve_length_mm=optional("curve_length_mm", _length),
        lead_in_mm=_length(where, "lead_in_mm", fields["lead_in_mm"]) if "lead_in_mm" in fields else 0.0,
        lead_out_mm=_length(where, "lead_out_mm", fields["lead_out_mm"]) if "lead_out_mm" in fields else 0.0,
        standoff_mm=optional("standoff_mm", _length),
        speed_mm_s=optional("speed_mm_s", _length),
        accuracy_mm=optional("accuracy_mm", _length),
        gun_signal=optional("gun_signal", _count),
        frame=parse_xyzoat(fields["frame"], f"{where}: header field frame") if "frame" in fields else None,
        n_segments=optional("n_segments", _count),
        n_lines=optional("n_lines", _count),
        n_arcs=optional("n_arcs", _count),
        contours=_contours(where, fields),
        contour_order=contour_order,
        speed_on=_speed_on(where, get("speed_on")),
    )


def _speed_on(where: str, raw: str | None) -> str | None:
    if raw is not None and raw not in SPEED_ON:
        raise InputError(f"{where}: header field speed_on={raw!r}: expected one of {', '.join(SPEED_ON)}")
    return raw


RECORD_MARK = "coatsim:"
_AFTER_SPACE, _JOINED = "coatsim+", "coatsim&"  # a field continued after one space, or directly
_MARK_WIDTH = len(RECORD_MARK) + 1


def _chunks(text: str, room: int) -> list[tuple[str, str]]:
    """(mark, content) lines of at most ``room`` characters of content holding ``text`` (single
    spaces between words): whole words where they fit, a longer word split."""
    out: list[tuple[str, str]] = []
    mark, current = RECORD_MARK, ""
    for index, word in enumerate(text.split(" ")):
        if index and len(current) + 1 + len(word) <= room:
            current += " " + word
            continue
        if index:
            out.append((mark, current))
            mark, current = _AFTER_SPACE, ""
        while len(word) > room:
            out.append((mark, word[:room]))
            mark, word = _JOINED, word[room:]
        current = word
    out.append((mark, current))
    return out


def comment_lines(info: ProcessInfo, width: Optional[int] = None,
                  clean: Callable[[str], str] = lambda text: text) -> list[str]:
    """The record of ``info`` as comment texts (without the language's comment marks) of at most
    ``width`` characters (None: one line per field); ``clean`` makes a value safe inside the
    language's comment (e.g. no parentheses in G-code), runs of whitespace become one space."""
    if width is not None and width <= _MARK_WIDTH + 1:
        raise ValueError(f"a record comment needs more than {_MARK_WIDTH + 1} characters")
    lines = []
    for key, value in encode(info):
        text = f"{key}={' '.join(clean(value).split())}"
        room = len(text) if width is None else width - _MARK_WIDTH
        lines += [f"{mark} {content}" for mark, content in _chunks(text, max(room, 1))]
    return lines


def read_comment_lines(texts: Iterable[str], where: str) -> ProcessInfo:
    """The record held in a program's comment texts (any other comment is skipped); the empty
    record when there is none."""
    fields: list[str] = []
    for raw in texts:
        text = raw.strip()
        head, rest = text[:len(RECORD_MARK)], text[len(RECORD_MARK):].strip()
        if head == RECORD_MARK:
            fields.append(rest)
        elif head in (_AFTER_SPACE, _JOINED) and fields:
            fields[-1] += (" " if head == _AFTER_SPACE else "") + rest
    pairs = [tuple(part.strip() for part in f.split("=", 1)) for f in fields if "=" in f]
    return decode(pairs, where)  # type: ignore[arg-type]
