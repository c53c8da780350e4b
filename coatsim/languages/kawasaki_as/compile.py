"""Flatten the nested statements of a program into code with jumps, so that GOTO may leave
(or enter) any block, as on the controller. Each op is a tuple ``(opcode, line, ...)``."""

from __future__ import annotations

from dataclasses import dataclass, field

from coatsim.core.errors import InputError
from coatsim.languages.kawasaki_as import ast

EXEC, JUMP, JUMP_IF_FALSE, JUMP_IF_TRUE, FOR_INIT, FOR_TEST, FOR_NEXT, CASE = range(8)


@dataclass(frozen=True)
class Code:
    """The ops of one program; ``loops`` names the loop a backward jump closes (for the
    interpreter's messages): op index -> (line, what); ``endless`` the backward jumps that close
    a loop with no way out (no jump out of it, no RETURN, STOP or HALT in it, a WHILE or
    DO ... UNTIL whose condition is a constant that never ends it): a cycle the cell repeats;
    ``exits`` per backward jump whose loop does more than wait (TWAIT, SWAIT, WAIT) and is left
    only by conditional jumps, those jumps' op indices (a loop ended by what the cell tells: see
    coatsim.languages.kawasaki_as.loops)."""

    ops: tuple[tuple, ...]
    loops: dict[int, tuple[int, str]]
    endless: frozenset[int] = frozenset()
    exits: dict[int, tuple[int, ...]] = field(default_factory=dict)


class _Compiler:
    def __init__(self, program: ast.Program) -> None:
        self.program = program
        self.ops: list[list] = []
        self.labels: dict[str, int] = {}
        self.label_lines: dict[str, int] = {}
        self.gotos: list[tuple[int, str, int]] = []  # (op index, label, line)
        self.exits: list[list[int]] = []  # per open loop: op indices of its EXITs
        self.loops: dict[int, tuple[int, str]] = {}
        self.slots = 0

    def emit(self, *op) -> int:
        self.ops.append(list(op))
        return len(self.ops) - 1

    def here(self) -> int:
        return len(self.ops)

    def body(self, statements: tuple[ast.Statement, ...]) -> None:
        for st in statements:
            self.statement(st)

    def statement(self, st: ast.Statement) -> None:
        """Compile one statement: a block into its jumps, anything else into one EXEC."""
        compile_block = self._BLOCKS.get(type(st))
        if compile_block is None:
            self.emit(EXEC, st.line, st)
        else:
            compile_block(self, st)

    def _label(self, st: ast.Label) -> None:
        if st.name in self.labels:
            raise InputError(f"{self.program.source}:{st.line}: label {st.name} is defined twice in program "
                             f"'{self.program.name}' (first at line {self.label_lines[st.name]})")
        self.labels[st.name], self.label_lines[st.name] = self.here(), st.line

    def _goto(self, st: ast.Goto) -> None:
        index = self.emit(JUMP if st.condition is None else JUMP_IF_TRUE, st.line, st.condition, None)
        self.gotos.append((index, st.label, st.line))

    def _if(self, st: ast.If) -> None:
        ends = []
        for condition, body in st.branches:
            test = self.emit(JUMP_IF_FALSE, st.line, condition, None)
            self.body(body)
            ends.append(self.emit(JUMP, st.line, None, None))
            self.ops[test][3] = self.here()
        self.body(st.orelse)
        for i in ends:
            self.ops[i][3] = self.here()

    def _while(self, st: ast.While) -> None:
        top = self.here()
        test = self.emit(JUMP_IF_FALSE, st.line, st.condition, None)
        self.loop(st.body)
        back = self.emit(JUMP, st.end_line, None, top)
        self.loops[back] = (st.line, "WHILE loop")
        self.ops[test][3] = self.here()
        self.close_loop()

    def _do_until(self, st: ast.DoUntil) -> None:
        top = self.here()
        self.loop(st.body)
        back = self.emit(JUMP_IF_FALSE, st.end_line, st.condition, top)
        self.loops[back] = (st.line, "DO ... UNTIL loop")
        self.close_loop()

    def _for(self, st: ast.For) -> None:
        slot = self.slots
        self.slots += 1
        self.emit(FOR_INIT, st.line, st, slot)
        test = self.emit(FOR_TEST, st.line, st, slot, None)
        self.loop(st.body)
        back = self.emit(FOR_NEXT, st.end_line, st, slot, test)
        self.loops[back] = (st.line, "FOR loop")
        self.ops[test][4] = self.here()
        self.close_loop()

    def _case(self, st: ast.Case) -> None:
        case = self.emit(CASE, st.line, st, [], None, None)
        ends = []
        for _, body, _ in st.branches:
            self.ops[case][3].append(self.here())
            self.body(body)
            ends.append(self.emit(JUMP, st.line, None, None))
        self.ops[case][4] = self.here()
        if st.default is not None:
            self.body(st.default)
        self.ops[case][5] = self.here()
        for i in ends:
            self.ops[i][3] = self.here()

    def _exit(self, st: ast.Exit) -> None:
        if not self.exits:
            raise InputError(f"{self.program.source}:{st.line}: EXIT outside a loop (WHILE, DO, FOR)")
        self.exits[-1].append(self.emit(JUMP, st.line, None, None))

    _BLOCKS = {ast.Label: _label, ast.Goto: _goto, ast.If: _if, ast.While: _while, ast.DoUntil: _do_until,
               ast.For: _for, ast.Case: _case, ast.Exit: _exit}

    def loop(self, body: tuple[ast.Statement, ...]) -> None:
        self.exits.append([])
        self.body(body)

    def close_loop(self) -> None:
        for i in self.exits.pop():
            self.ops[i][3] = self.here()

    def finish(self) -> Code:
        for index, label, line in self.gotos:
            if label not in self.labels:
                raise InputError(f"{self.program.source}:{line}: GOTO {label}: no such label in program "
                                 f"'{self.program.name}'")
            target = self.labels[label]
            self.ops[index][3] = target
            if target <= index:
                self.loops[index] = (self.label_lines[label], f"GOTO {label} loop")
        ops = tuple(tuple(op) for op in self.ops)
        exits = {back: tests for back in self.loops if (tests := _exit_tests(ops, back))}
        return Code(ops, self.loops, frozenset(back for back in self.loops if _endless(ops, back)), exits)


def _exit_tests(ops: tuple[tuple, ...], back: int) -> tuple[int, ...]:
    """The conditional jumps that leave the loop closed by ``back`` (``back`` itself when it is
    one: falling through it leaves), or () when it has any other way out (a FOR, a jump, RETURN,
    STOP, HALT, a CASE branch out of it) or none, or when it only waits (a loop that changes
    nothing: LoopControl.waited)."""
    op = ops[back]
    if op[0] == FOR_NEXT:
        return ()
    inside = range(op[3], back + 1)
    tests, works = [], False
    for k in range(op[3], back + 1):
        kind = ops[k][0]
        if kind == EXEC:
            st = ops[k][2]
            if isinstance(st, ast.Return) or (isinstance(st, ast.Stop) and st.op != "PAUSE"):
                return ()
            works = works or not isinstance(st, (ast.Twait, ast.Swait, ast.Wait))
        elif kind in (JUMP_IF_FALSE, JUMP_IF_TRUE) and not _constant(ops[k][2], kind == JUMP_IF_FALSE):
            if k == back or ops[k][3] not in inside:
                tests.append(k)
        elif (kind == JUMP and ops[k][3] not in inside) or (kind == FOR_TEST and ops[k][4] not in inside):
            return ()
        elif kind == CASE and any(t not in inside for t in (*ops[k][3], ops[k][4], ops[k][5])):
            return ()
    return tuple(tests) if works else ()


def _endless(ops: tuple[tuple, ...], back: int) -> bool:
    """Whether the loop closed by the backward jump at ``back`` has no way out: every jump
    inside it stays inside it (its own back jump aside), a loop test can never end it (a
    constant condition), and no RETURN, STOP or HALT is in it."""
    op = ops[back]
    if op[0] in (FOR_NEXT, JUMP_IF_TRUE) or (op[0] == JUMP_IF_FALSE and not _constant(op[2], False)):
        return False  # (a FOR loop ends; falling through a conditional GOTO or an UNTIL leaves the loop)
    top = op[3]
    inside = range(top, back + 1)
    for k in range(top, back):
        kind = ops[k][0]
        if kind == EXEC:
            st = ops[k][2]
            if isinstance(st, ast.Return) or (isinstance(st, ast.Stop) and st.op != "PAUSE"):
                return False
        elif kind == JUMP_IF_FALSE and _constant(ops[k][2], True):
            continue  # (WHILE TRUE: its test never jumps)
        elif kind in (JUMP, JUMP_IF_FALSE, JUMP_IF_TRUE) and ops[k][3] not in inside:
            return False
        elif kind == FOR_TEST and ops[k][4] not in inside:
            return False
        elif kind == CASE and any(t not in inside for t in (*ops[k][3], ops[k][4], ops[k][5])):
            return False
    return True


def _constant(condition: ast.Expr, truth: bool) -> bool:
    """Whether ``condition`` is a constant (TRUE, ON, 1, FALSE, ...) of truth ``truth``."""
    return isinstance(condition, ast.Num) and (condition.value != 0) == truth


def compile_program(program: ast.Program) -> Code:
    """The flat code of ``program``; InputError for a GOTO to a missing label, a label
    defined twice or an EXIT outside a loop."""
    c = _Compiler(program)
    c.body(program.body)
    return c.finish()
