"""What a backward jump of an AS program does (a part of the interpreter, which provides the
call ``stack``, the ``controller``, ``changes``, ``unknowns``, ``signals``, ``served``, the step
budget and its messages).

A loop with no way out (coatsim.languages.kawasaki_as.compile) is the cycle the cell repeats: it
runs once and the run ends there. A loop whose pass changed nothing (no motion, no value, no
signal) would repeat the same way for ever: if it read what the twin does not know it waits for
the cell and is taken as ended, else it never ends (ExecutionError, at once). Any other loop runs
until the step budget, whose message names it.
"""

from __future__ import annotations

from coatsim.core.errors import ExecutionError
from coatsim.languages.kawasaki_as.compile import Code
from coatsim.languages.kawasaki_as.statements_exec import StopProgram


class LoopControl:
    """Backward jumps of a running program."""

    def jump(self, code: Code, pc: int, target: int) -> int:
        """Where a jump at ``pc`` goes. Backward (a loop): a loop with no way out is a cycle the
        cell repeats, run once (the program ends there); a loop whose last pass changed nothing
        (no motion, no value, no signal) repeats the same way for ever: if it read what the twin
        does not know (an input, a timer, a message), it waits for that and is taken as ended
        (the jump is not taken), else it never ends (ExecutionError)."""
        if target > pc:
            return target
        line, what = code.loops.get(pc, (self.line, "loop"))
        self.last_loop = (self.source, line, what)
        if pc in code.endless:
            self.warn(f"cycle:{self.where()}", f"the {what} of line {line} has no way out: a cycle the "
                      "cell repeats; the twin runs it once and ends there")
            raise StopProgram()
        state = (len(self.controller.moves), self.changes)
        reads = (self.unknowns.reads, self.signals.unknown_reads, self.unknowns.messages)
        visits = self.stack[-1].visits
        last = visits.get(pc)
        visits[pc] = (state, reads)
        if last is None or last[0] != state:
            return target
        if reads != last[1]:
            return self.waited(pc, line, what, [r != r0 for r, r0 in zip(reads, last[1])])
        raise self.failure(f"the {what} of line {line} repeats with nothing changing: it never ends (end it with "
                           "STOP or HALT, or change what it tests)")

    def waited(self, pc: int, line: int, what: str, read: list[bool]) -> int:
        """A loop that waits for what the twin does not know (``read``: an unknown value, an input
        not given, a message) is taken as ended: where it goes on. One that waits for an input or a
        message serves the cell: when it waits again, the run has read a pass of the loop that
        serves and ends there (it would take the same turn for ever)."""
        reads = self.unknowns.last if read[0] else "an input not given" if read[1] else "a message"
        if read[1] or read[2]:
            place = (self.stack[-1].program.name, pc)
            if place in self.served:
                self.warn(f"served:{self.where()}", f"the {what} of line {line} waits again for {reads}: the "
                          "twin read one pass of the loop that serves the cell and ends there")
                raise StopProgram()
            self.served.add(place)
        self.warn(f"wait:{self.where()}", f"the {what} of line {line} waits for what the twin does not know "
                  f"(it reads {reads}, and nothing changes); taken as ended")
        return pc + 1

    def budget_error(self) -> ExecutionError:
        if self.last_loop is not None:
            source, line, what = self.last_loop
            return ExecutionError(f"{source}:{line}: the program ran {self.max_steps} steps without ending, in the "
                                  f"{what} of line {line}; an endless cycle? (end it with STOP or HALT)")
        return self.failure(f"the program ran {self.max_steps} steps without ending")

