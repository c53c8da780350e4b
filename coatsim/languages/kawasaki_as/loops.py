"""What a backward jump of an AS program does (a part of the interpreter, which provides the
call ``stack``, the ``controller``, ``changes``, ``unknowns``, ``signals``, ``served``, the step
budget and its messages).

A loop with no way out (coatsim.languages.kawasaki_as.compile) is the cycle the cell repeats: it
runs once and the run ends there. A loop whose pass changed nothing (no motion, no value, no
signal) would repeat the same way for ever: if it read what the twin does not know it waits for
the cell and is taken as ended, else it never ends (ExecutionError, at once). A loop left only
by conditions that turn on nothing but what the twin does not know (variables no file or value
gives, inputs not given: ``WHILE NOT SIG(1020) DO``) and that does more than wait ends when the
cell says so: it runs once and goes on at its first way out. Any other loop runs until the step budget, whose message
names it.
"""

from __future__ import annotations

from typing import Optional

from coatsim.core.errors import ExecutionError
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.compile import EXEC, Code
from coatsim.languages.kawasaki_as.main_program import nodes
from coatsim.languages.kawasaki_as.parser import key as norm
from coatsim.languages.kawasaki_as.printer import expr_text
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
        exits = code.exits.get(pc, ())
        blind = [self.stack[-1].blind.get(k, "") for k in exits]
        if exits and all(blind) and self.untouched(code, pc, exits):
            return self.left(code, pc, line, what, exits, blind)
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

    def left(self, code: Code, pc: int, line: int, what: str, exits: tuple[int, ...], reads: list[str]) -> int:
        """A loop that does more than wait but is left only by conditions on what the twin does not know
        (``reads`` per exit of ``exits``) ends when the cell says so: run once, it is left where
        its first exit leaves it."""
        conditions = "; ".join(f"{expr_text(code.ops[k][2])} (line {code.ops[k][1]}, it reads {r})"
                               for k, r in zip(exits, reads))
        self.warn(f"outside:{self.where()}", f"the {what} of line {line} ends only on what the twin does not know: "
                  f"{conditions}; the twin runs it once and leaves it (give those a value to run it as written)")
        return pc + 1 if exits[0] == pc else code.ops[exits[0]][3]

    def untouched(self, code: Code, pc: int, exits: tuple[int, ...]) -> bool:
        """Whether nothing in the loop closed at ``pc`` (nor in what it CALLs) names a variable or
        switches a signal its exit conditions read: what ends it comes from outside."""
        statements = [op[2] for op in code.ops[code.ops[pc][3]:pc + 1] if op[0] == EXEC]
        names: set[str] = set()
        signals: set[int] = set()
        called: set[str] = set()
        while statements:
            for node in nodes(statements.pop()):
                if isinstance(node, ast.Name):
                    names.add(norm(node.name))
                elif isinstance(node, ast.CallProgram):
                    callee = self.programs.get(node.program.lower()) if isinstance(node.program, str) else None
                    if callee is None and not isinstance(node.program, str):
                        return False  # (a program named by a string: it may set anything)
                    if callee is not None and callee.name.lower() not in called:
                        called.add(callee.name.lower())
                        statements.extend(callee.body)
                elif isinstance(node, (ast.Signal, ast.Pulse, ast.Bits)):
                    numbers = [self.signal_number(e) for e in (node.outputs if isinstance(node, ast.Signal) else
                                                               (node.signal,) if isinstance(node, ast.Pulse) else (None,))]
                    if None in numbers:
                        return False  # (a signal number computed, or a group of BITS: it may be any)
                    signals.update(numbers)
        for k in exits:
            read = list(nodes(code.ops[k][2]))
            if any(norm(n.name) in names for n in read if isinstance(n, ast.Name)):
                return False
            for n in read:
                if isinstance(n, ast.Call) and n.name.upper() == "SIG" and \
                        any(self.signal_number(a) in signals or self.signal_number(a) is None for a in n.args):
                    return False
        return True

    def blind(self, e: ast.Expr, signal: bool) -> str:
        """What a condition that read an unknown turns on, when that is all it turns on (every
        variable it names has no value: the unknowns, and an input not given if ``signal``);
        "" when it also names a variable that has one (a counter may end the loop)."""
        numbers = _signal_names(e)  # (a constant naming the input, di.stop = 1010: the input is what is unknown)
        names = [n for n in dict.fromkeys(_names(e)) if norm(n) not in numbers]
        if any(norm(n) not in self.unknowns.first for n in names):
            return ""
        return ", ".join(names + (["an input not given"] if signal else []))

    def signal_number(self, e) -> Optional[int]:
        """A signal number written as a number or as a variable with a value (a constant of .REALS,
        ``SIG(di.stop)``): its absolute value, else None (computed: it may be any)."""
        if isinstance(e, ast.Unary) and e.op in "-+":
            e = e.operand
        if isinstance(e, ast.Name) and not e.index and e.kind == "value" and self.has_real(e):
            return int(abs(self.get_real(e)))
        return int(abs(e.value)) if isinstance(e, ast.Num) else None

    def budget_error(self) -> ExecutionError:
        if self.last_loop is not None:
            source, line, what = self.last_loop
            return ExecutionError(f"{source}:{line}: the program ran {self.max_steps} steps without ending, in the "
                                  f"{what} of line {line}; an endless cycle? (end it with STOP or HALT)")
        return self.failure(f"the program ran {self.max_steps} steps without ending")


def _names(e) -> list[str]:
    """The variables an expression names (as written)."""
    return [n.name for n in nodes(e) if isinstance(n, ast.Name)]


def _signal_names(e) -> set[str]:
    """The variables an expression names inside the signal numbers of its SIG(...) calls."""
    return {norm(n.name) for call in nodes(e) if isinstance(call, ast.Call) and call.name.upper() == "SIG"
            for a in call.args for n in nodes(a) if isinstance(n, ast.Name)}
