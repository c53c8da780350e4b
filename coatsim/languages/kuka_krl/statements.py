"""KRL statements: structures (``IF``, ``FOR``, ``WHILE``, ``LOOP``, ``REPEAT``, ``SWITCH``), the
simple statements (motions, ``WAIT``, ``HALT``, ``TRIGGER``, ``BAS``, a bare ``INI``,
declarations) and assignments, ``$OUT`` with the advance run and routine calls. The
interpreter's Statements part (see :mod:`.interpreter`, which says what the twin models)."""

from __future__ import annotations

from typing import Any

from coatsim.languages.kuka_krl.blocks import Block
from coatsim.languages.kuka_krl.motion import DEFAULT_VEL_CP_M_S, MOTION_DATA
from coatsim.languages.kuka_krl.parser import Line, split_commas, statement_text
from coatsim.languages.script import nodes as n
from coatsim.languages.script.flow import Halt, LeaveLoop, Return
from coatsim.languages.script.tokens import NAME, OP
from coatsim.path.toolpath import Dwell

MAX_STEPS = 1_000_000
_NOTED = {"INTERRUPT", "BRAKE", "RESUME", "ANIN", "ANOUT", "SIGNAL", "ENUM", "STRUC", "EXT", "EXTFCT", "IMPORT"}

class Statements:
    """The statements of an Interpreter run."""

    def _cond(self, tokens) -> bool:
        value = self.eval(self.expr(tokens))
        if not isinstance(value, bool):
            raise self.error("a condition must be TRUE or FALSE")
        return value

    def structure(self, b: Block) -> None:
        self.line = b.line
        toks = b.head.tokens
        if b.kind == "IF":
            then = next((k for k, t in enumerate(toks) if t.kind == NAME and t.text.upper() == "THEN"), len(toks))
            branch = 0 if self._cond(toks[1:then]) else 1
            if branch < len(b.parts):
                self.block(b.parts[branch][1])
        elif b.kind == "WHILE":
            while self._cond(toks[1:]):
                self.block(b.parts[0][1])
                self.steps += 1
                if self.steps > MAX_STEPS:
                    raise self.failure("a WHILE loop that never ends")
        elif b.kind in ("LOOP", "REPEAT"):
            try:
                while True:
                    self.block(b.parts[0][1])
                    self.steps += 1
                    if self.steps > MAX_STEPS:
                        raise self.failure(f"a {b.kind} loop that never ends")
                    if b.kind == "REPEAT" and self._cond(b.tail.tokens[1:]):
                        break
            except LeaveLoop:
                pass
        elif b.kind == "FOR":
            self._for(b)
        elif b.kind == "SWITCH":
            value = self.eval(self.expr(toks[1:]))
            for opener, body in b.parts:
                if opener.word == "DEFAULT" or any(self.eval(self.expr(part)) == value
                                                   for part in split_commas(opener.tokens[1:])):
                    self.block(body)
                    return

    def _for(self, b: Block) -> None:
        toks = list(b.head.tokens)
        words = [t.text.upper() if t.kind == NAME else "" for t in toks]
        if "TO" not in words or len(toks) < 4 or toks[2].text != "=":
            raise self.error("FOR needs: FOR i = start TO end [STEP s]")
        to = words.index("TO")
        step_at = words.index("STEP") if "STEP" in words else len(toks)
        start = self._num(self.eval(self.expr(toks[3:to])))
        stop = self._num(self.eval(self.expr(toks[to + 1:step_at])))
        step = self._num(self.eval(self.expr(toks[step_at + 1:]))) if step_at < len(toks) else 1.0
        if step == 0:
            raise self.error("FOR ... STEP 0 never ends")
        var = n.Name(toks[1].text, toks[1].line)
        value = start
        try:
            while (value <= stop) if step > 0 else (value >= stop):
                self.assign(var, value) if self._declared(var.name) else self._local(var.name, value)
                self.block(b.parts[0][1])
                value += step
        except LeaveLoop:
            pass

    def _declared(self, name: str) -> bool:
        key = name.upper()
        return (bool(self.frames) and key in self.frames[-1]) or key in self.globals

    def _local(self, name: str, value: Any) -> None:
        self.frames[-1][name.upper()] = value

    def simple(self, ln: Line) -> None:
        toks = ln.tokens
        word = ln.word
        if len(toks) == 2 and toks[1].text == ":":
            return  # a label
        if word in ("PTP", "LIN", "CIRC", "PTP_REL", "LIN_REL"):
            self.motion(ln)
        elif word == "CONTINUE":
            self.continue_next = True
            return
        elif word == "WAIT":
            self._stop_previous()
            if len(toks) > 1 and toks[1].text.upper() == "SEC":
                seconds = self._num(self.eval(self.expr(toks[2:])))
                self.dwells.append(Dwell(len(self.moves) - 1, seconds, self.spraying, ln.line))
            elif len(toks) > 1 and toks[1].text.upper() == "FOR" and not self._cond(toks[2:]):
                self.warn(f"wait{ln.line}", "WAIT FOR waits for a condition that is false here; coatsim goes on as if "
                                            "it came true")
        elif word == "HALT":
            self._stop_previous()
            raise Halt(f"{self.where()}: HALT")
        elif word == "RETURN":
            raise Return(self.eval(self.expr(toks[1:])) if len(toks) > 1 else None)
        elif word == "EXIT":
            raise LeaveLoop()
        elif word == "TRIGGER":
            self.trigger(ln)
        elif word in _NOTED or (word == "GLOBAL" and len(toks) > 1 and toks[1].text.upper() == "INTERRUPT"):
            self.warn("interrupt", f"{toks[0].text} ...: interrupts are noted, not run")
        elif word == "BAS":
            self.bas(ln)
        elif word == "INI" and len(toks) == 1:  # the INI line of older programs: BAS(#INITMOV,0)
            self.system["$VEL"].fields["CP"] = DEFAULT_VEL_CP_M_S
        elif word == "PULSE":
            self.warn("pulse", "PULSE: a timed output is not simulated")
        elif self.declaration(ln, self.frames[-1] if self.frames else self.globals):
            pass
        else:
            self.statement(ln)
        self.continue_next = False

    def statement(self, ln: Line) -> None:
        toks = ln.tokens
        eq = next((k for k, t in enumerate(toks) if t.kind == OP and t.text == "="), None)
        if eq is None:
            e = self.expr(toks)
            if isinstance(e, n.Call):
                routine = self.routines.get(e.name.lower())
                if routine is None:
                    self.skipped.append(f"{self.where()}: {e.name} skipped: no routine of that name in the files "
                                        "loaded")
                    return
                self.call(routine, e.args)
                return
            raise self.error(f"expected a statement, found {toks[0].text!r}")
        target = self.expr(toks[:eq])
        if isinstance(target, n.Name) and target.name.upper() in MOTION_DATA:
            self.motion_data_set(target.name.upper(), toks[eq + 1:])
            return
        value = self.eval(self.expr(toks[eq + 1:]))
        if isinstance(target, n.Index) and isinstance(target.base, n.Name) and \
                target.base.name.upper() in ("$OUT", "$OUT_C"):
            number = int(self._num(self.eval(target.index[0])))
            text = statement_text(toks)
            if target.base.name.upper() == "$OUT_C":
                self.switch(number, bool(value), text, "next")
            elif self.continue_next:
                self.warn("continue", "an output set after CONTINUE switches in the advance run, up to $ADVANCE "
                                      "motions before this point; the twin switches it as the next motion starts")
                self.switch(number, bool(value), text, "next")
            else:
                self._stop_previous()  # the advance run stops: the motion before ends at rest
                self.switch(number, bool(value), text, "now")
            return
        self.assign(target, value)
