"""What coatsim may write into a KRL program: names and comment text.

A KRL name is at most 24 characters: letters, digits, '_' and '$', not starting with a digit
(KUKA System Software 8, "Programming for system integrators": names); keywords are not names;
the program's name is its file's name (``DEF name`` in ``name.src``). Comments are printable
ASCII on one line.
"""

from __future__ import annotations

import re

from coatsim.core.errors import InputError
from coatsim.languages.script.names import sanitize_comment

MAX_NAME_LENGTH = 24
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
KEYWORDS = frozenset("""AND ANIN ANOUT B_AND B_NOT B_OR B_EXOR BOOL BRAKE C_DIS C_ORI C_PTP C_VEL CASE CAST_FROM
CAST_TO CHAR CIRC CIRC_REL CONST CONTINUE DELAY DECL DEF DEFAULT DEFDAT DEFFCT DELAY DO ELSE END ENDDAT ENDFCT ENDFOR
ENDIF ENDLOOP ENDSWITCH ENDWHILE ENUM EXIT EXT EXTFCT FALSE FOR GLOBAL GOTO HALT IF IMPORT INT INTERRUPT IS LIN
LIN_REL LOOP MAX MIN NOT OR PRIO PTP PTP_REL PUBLIC REAL REPEAT RESUME RETURN SEC SIGNAL STEP STRUC SWITCH THEN TO
TRIGGER TRUE UNTIL WAIT WHEN WHILE EXOR""".split())


def check_name(name: str, what: str = "program name") -> str:
    """``name`` if it is a valid KRL name; InputError (one line) otherwise."""
    if not isinstance(name, str) or not _NAME.match(name) or len(name) > MAX_NAME_LENGTH or name.upper() in KEYWORDS:
        shown = sanitize_comment(str(name))
        raise InputError(f"{what} {shown!r} is not a valid KRL name: letters, digits and '_', not first a digit, at "
                         f"most {MAX_NAME_LENGTH} characters, not a keyword", parameters=(what,))
    return name


def program_name(text: str) -> str:
    """A valid KRL program name from any text (lower case, as file names are)."""
    name = re.sub(r"[^a-z0-9_]+", "_", text.lower()).strip("_")
    if not name or name[0].isdigit():
        name = "p" + name
    name = name[:MAX_NAME_LENGTH].rstrip("_") or "coat"
    return name + "_" if name.upper() in KEYWORDS else name
