"""What coatsim may write into a program: AS identifiers and comment text.

An AS name is letters, digits, '.' and '_', starting with a letter, at most 15 characters
(the controller's limit). Comment text is printable ASCII on one line: a line break in a comment
would start a new statement (program injection).
"""

from __future__ import annotations

import re

from coatsim.core.errors import InputError

MAX_NAME_LENGTH = 15
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9._]*\Z")
MAX_COMMENT = 200


def check_name(name: str, what: str = "program name") -> str:
    """``name`` if it is a valid AS identifier; InputError (one line) otherwise."""
    if not isinstance(name, str) or not _NAME.match(name) or len(name) > MAX_NAME_LENGTH:
        raise InputError(f"{what} {sanitize_comment(str(name))!r} is not a valid AS name: letters, digits, '.' and "
                         f"'_', first a letter, at most {MAX_NAME_LENGTH} characters", parameters=(what,))
    return name


def program_name(text: str) -> str:
    """A valid AS program name from any text: lower-case letters, digits and '_', starting
    with a letter, at most 15 characters."""
    name = re.sub(r"[^a-z0-9_]+", "_", text.lower()).strip("_")
    if not name or not name[0].isalpha():
        name = "c" + name
    return name[:MAX_NAME_LENGTH].rstrip("_") or "coat"


def sanitize_comment(text: str, limit: int | None = MAX_COMMENT) -> str:
    """``text`` as one line of printable ASCII (anything else becomes '?'), at most ``limit``
    characters (None: any length, for the header fields coatsim reads back)."""
    clean = "".join(ch if 32 <= ord(ch) < 127 else "?" for ch in text)
    return clean if limit is None or len(clean) <= limit else clean[:limit - 3] + "..."
