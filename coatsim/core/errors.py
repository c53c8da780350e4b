"""Errors a user can cause, each with the exit code the CLI returns for it.

Exit codes: 0 success; 1 a gate failed; 2 invalid input; 3 cannot execute.
"""

from __future__ import annotations

import re
from typing import Mapping


class CoatsimError(Exception):
    """Base of every error coatsim reports to a user; the message is one line.

    ``parameters`` names the parameters the message speaks of, in the library's terms (e.g.
    ``tolerance_mm``), so that a caller with other words for them (the command line's flags, a
    scenario's keys) can say them its own way.
    """

    exit_code: int = 2

    def __init__(self, message: str, *, parameters: tuple[str, ...] = ()) -> None:
        super().__init__(message)
        self.parameters = parameters

    def reworded(self, words: Mapping[str, str]) -> CoatsimError:
        """The same error with each of its parameters that ``words`` names said that way (where
        the message first names it)."""
        text = str(self)
        for name in self.parameters:
            if name in words:
                text = re.sub(rf"(?<![\w.-]){re.escape(name)}(?![\w])", words[name], text, count=1)
        return self._saying(text)

    def prefixed(self, where: str) -> CoatsimError:
        """The same error (its class and details kept) with ``where`` said before its message."""
        return self._saying(f"{where}: {self}")

    def _saying(self, text: str) -> CoatsimError:
        new = type(self).__new__(type(self))  # not copy.copy: it calls __init__ with the message alone
        new.__dict__.update(self.__dict__)
        new.args = (text,)
        return new


class InputError(CoatsimError):
    """Invalid input: usage, file, schema or program syntax (exit 2)."""

    exit_code = 2


class EmptyRegionOfInterest(InputError):
    """No part of the surface is measured: the spray misses the part or the edge band covers it
    (each command says which of its settings to change)."""


class ExecutionError(CoatsimError):
    """The program cannot execute: unreachable pose, joint limit, infeasible timing (exit 3)."""

    exit_code = 3


class GateFailure(CoatsimError):
    """An accuracy gate failed (exit 1)."""

    exit_code = 1


class CoatsimWarning(UserWarning):
    """Something a user should know that does not stop the run; the CLI prints it on one line."""


# a number, or a number with a typo or a unit ('1.2.3', '2mm', '1e5x'): starts like a number
_NUMBER_LIKE = re.compile(r"^(?:[-+0-9.,eE_ ]{1,24}|[-+]?\.?[0-9][0-9A-Za-z.,_%+-]{0,15})$")
_NAME_LIKE = re.compile(r"^[A-Za-z_][A-Za-z0-9_ ()\[\]/.-]{0,23}$")


def shown(field: str, names: bool = False) -> str:
    """How an error quotes a field read from a file: a short number-like field (and, with
    ``names``, a short column name) as is, anything else only by its length, so that an error
    never echoes the content of a file that is not what it was asked to read (a scenario that
    points at ``/etc/passwd``)."""
    text = field.strip()
    if _NUMBER_LIKE.match(text) or (names and _NAME_LIKE.match(text)):
        return repr(text)
    return f"a {len(text)}-character text" if text else "an empty field"


#: Longest message line a command prints; a longer one keeps its start and end.
MAX_MESSAGE_CHARS = 1000
_CONTROL = re.compile(r"[\x00-\x1f\x7f-\x9f\u2028\u2029]")


def one_line(text: str, limit: int = MAX_MESSAGE_CHARS) -> str:
    """``text`` as one printable line of at most ``limit`` characters: control characters (line
    breaks, terminal escapes) shown escaped, a long middle left out with a count."""
    flat = _CONTROL.sub(lambda m: repr(m.group())[1:-1], str(text))
    if len(flat) <= limit:
        return flat
    keep = limit - 40
    return f"{flat[:keep * 3 // 4]} ... ({len(flat) - keep} characters left out) ... {flat[-(keep // 4):]}"
