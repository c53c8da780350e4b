"""Control flow of the statement languages (RAPID, KRL) as exceptions their interpreters raise
and catch: a routine returns (with its value), a jump goes to a label (GOTO), a loop is left
(KRL ``EXIT``), the program halts (RAPID ``Stop``/``EXIT``, KRL ``HALT``)."""

from __future__ import annotations

from typing import Any


class Return(Exception):
    """``RETURN [value]``."""

    def __init__(self, value: Any) -> None:
        super().__init__()
        self.value = value


class Jump(Exception):
    """``GOTO label`` at source ``line`` (0: not told)."""

    def __init__(self, label: str, line: int = 0) -> None:
        super().__init__(label)
        self.label, self.line = label, line


class LeaveLoop(Exception):
    """``EXIT`` out of the innermost loop."""


class Halt(Exception):
    """The program ends here; ``how`` says where and by what (``prog.mod:9: Stop``)."""

    def __init__(self, how: str) -> None:
        super().__init__(how)
        self.how = how
