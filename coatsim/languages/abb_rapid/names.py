"""What coatsim may write into a RAPID module: identifiers and comment text.

A RAPID identifier is a letter followed by letters, digits and '_', at most 32 characters
(ABB, Technical reference manual — RAPID overview, "Basic elements: identifiers"); reserved
words are not identifiers. Comment text is printable ASCII on one line.
"""

from __future__ import annotations

import re

from coatsim.core.errors import InputError
from coatsim.languages.script.names import sanitize_comment

MAX_NAME_LENGTH = 32
_NAME = re.compile(r"[A-Za-z][A-Za-z0-9_]*\Z")
RESERVED = frozenset("""ALIAS AND BACKWARD CASE CONNECT CONST DEFAULT DIV DO ELSE ELSEIF ENDFOR ENDFUNC ENDIF
ENDMODULE ENDPROC ENDRECORD ENDTEST ENDTRAP ENDWHILE ERROR EXIT FALSE FOR FROM FUNC GOTO IF INOUT LOCAL MOD MODULE
NOSTEPIN NOT NOVIEW OR PERS PROC RAISE READONLY RECORD RETRY RETURN STEP SYSMODULE TEST THEN TO TRAP TRUE TRYNEXT
UNDO VAR VIEWONLY WHILE WITH XOR""".split())


def check_name(name: str, what: str = "program name") -> str:
    """``name`` if it is a valid RAPID identifier; InputError (one line) otherwise."""
    if not isinstance(name, str) or not _NAME.match(name) or len(name) > MAX_NAME_LENGTH or name.upper() in RESERVED:
        shown = sanitize_comment(str(name))
        raise InputError(f"{what} {shown!r} is not a valid RAPID name: letters, digits and '_', first a letter, at most "
                         f"{MAX_NAME_LENGTH} characters, not a reserved word", parameters=(what,))
    return name


def program_name(text: str) -> str:
    """A valid RAPID module name from any text."""
    name = re.sub(r"[^A-Za-z0-9_]+", "_", text).strip("_")
    if not name or not name[0].isalpha():
        name = "m" + name
    name = name[:MAX_NAME_LENGTH].rstrip("_") or "coat"
    return name + "_" if name.upper() in RESERVED else name
