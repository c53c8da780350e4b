"""AS source text: bytes -> lines, and the syntax error every reader stage raises.

Controllers and editors save AS files as ASCII with CRLF or LF line ends; comments and strings
may hold text in a Windows code page (or UTF-8, sometimes with a byte-order mark). Only
comments and string literals may hold non-ASCII characters, so decoding as UTF-8 when the bytes
are valid UTF-8 and byte-for-byte (Latin-1) otherwise never changes what a statement means.
DOS transfer tools end a file with Ctrl-Z (0x1A), once or several times: a trailing run of them
is the end of the file.
"""

from __future__ import annotations

import re

from coatsim.core.errors import InputError

_END_OF_FILE = re.compile(r"\x1a[\x1a\s]*\Z")  # Ctrl-Z and what follows it at the end


class AsSyntaxError(InputError):
    """An AS program text does not parse; the message is ``source:line:col: ...``."""


def syntax_error(source: str, line: int, col: int, message: str) -> AsSyntaxError:
    return AsSyntaxError(f"{source}:{line}:{col}: {message}")


def split_lines(text: str) -> list[str]:
    """Lines of ``text`` for any of the \\n, \\r\\n and \\r conventions (a BOM and a trailing
    run of Ctrl-Z end-of-file bytes dropped)."""
    if text.startswith("\ufeff"):
        text = text[1:]
    text = _END_OF_FILE.sub("", text)
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    return lines
