"""What program names and comment text of several languages share: a name of upper-case letters,
digits and '_' made from any text (Fanuc TP, G-code), text cut to printable ASCII, a one-line
comment of bounded length (RAPID, KRL)."""

from __future__ import annotations

import re


def upper_case_name(text: str, max_length: int) -> str:
    """Upper-case letters, digits and '_' of ``text``, first a letter (``C`` put before a digit),
    at most ``max_length`` characters; ``COAT`` when nothing is left."""
    name = re.sub(r"[^A-Z0-9_]+", "_", text.upper()).strip("_")
    if not name or not name[0].isalpha():
        name = "C" + name
    return name[:max_length].rstrip("_") or "COAT"


def printable(text: str) -> str:
    """``text`` with every character outside printable ASCII as '?'."""
    return "".join(ch if 32 <= ord(ch) < 127 else "?" for ch in text)


def sanitize_comment(text: str, limit: int | None = 200) -> str:
    """``text`` as one line of printable ASCII, cut to ``limit`` characters (None: not cut)."""
    clean = printable(text)
    return clean if limit is None or len(clean) <= limit else clean[:limit - 3] + "..."
