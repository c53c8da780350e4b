"""RAPID instructions other than motions: outputs (a signal numbered by the digits its name ends
with, or by a ``variables`` entry), inputs, waits, data instructions (``Incr``,
``Decr``, ``Add``, ``Clear``), calls of the program's routines, late-bound calls ``%"name"%``
(the routine named by the string's value), and the instructions noted or passed over."""

from __future__ import annotations

import re
from dataclasses import replace
from typing import Optional

from coatsim.languages.abb_rapid import syntax as s
from coatsim.languages.abb_rapid.motion import MOVES
from coatsim.languages.script import nodes as n
from coatsim.languages.script.flow import Halt
from coatsim.path.reading import OutputSwitch
from coatsim.path.toolpath import Dwell

_IGNORED = {"confl", "confj", "singarea", "accset", "pathacclim", "tpwrite", "tperase", "tpshow", "errwrite",
            "corrclear", "corrcon", "corrdiscon", "waitrob", "idelete", "isleep", "iwatch", "ienable",
            "idisable", "clkreset", "clkstart", "clkstop", "gripload", "worldaccim", "cornerpathwarn", "setsysdata",
            "pathresol", "motionsup", "triggio", "triggequip", "triggint", "triggcheckio", "stoppmove",
            "startmove", "clearpath", "storepath", "restopath", "softact", "softdeact", "tuneservo", "retry",
            "trynext", "raise", "skipwarn", "load", "unload", "waitload", "eraseModule".lower(), "sectl", "conveyor"}
_INTERRUPTS = {"isignaldi", "isignaldo", "itimer", "isignalai", "isignalao", "isignalgi", "isignalgo", "ipers",
               "ierror", "connect"}
_UNSIMULATED = {"searchl", "searchc", "searchj", "movelsync", "movejsync", "movecsync", "moveext", "csspdeact",
                "indamove", "indcmove", "inddmove", "indrmove", "indreset", "pulsedo", "tpreadfk",
                "tpreadnum", "tpreaddnum"}
_DATA = {"incr", "decr", "add", "clear"}


class Instructions:
    """The instructions of an Interpreter that are not motions, and its signals."""

    def signal_number(self, name: str) -> Optional[int]:
        for given, text in self.options.variables.items():
            if given.lower() == name.lower():
                try:
                    return int(float(text))
                except (TypeError, ValueError):
                    return None
        m = re.search(r"(\d+)$", name)
        return int(m.group(1)) if m else None

    def _signal_name(self, e: n.Expr) -> str:
        if isinstance(e, n.Name):
            return e.name
        value = self.eval(e)
        if isinstance(value, str):
            return value
        raise self.error("expected a signal")

    def set_output(self, signal: n.Expr, on: bool, call, text: str) -> None:
        name = self._signal_name(signal)
        number = self.signal_number(name)
        gun = number == self.options.gun_signal
        if number is not None:
            self.outputs.add(number)
        else:
            self.unnumbered.setdefault(name.lower(), f"{name} ({self.source}:{call.line})")
        if gun:
            self.spraying = on
        if not any(sw.line == call.line and sw.source == self.source for sw in self.switches):
            self.switches.append(OutputSwitch(self.source, call.line, text + (f" (gun {'on' if on else 'off'})"
                                                                              if gun else "")))

    def signal_state(self, e: n.Expr, function: str) -> bool:
        name = self._signal_name(e)
        number = self.signal_number(name)
        if function == "doutput":
            return self.spraying if number == self.options.gun_signal else False
        if number is not None and number in self.options.inputs:
            return bool(self.options.inputs[number])
        self.unknowns.setdefault(name.lower(), f"{self.where()}: input {name} (taken as off)")
        return False

    def instruction(self, st: s.ProcCall) -> None:
        if st.late is not None:
            st = self.late_bound(st)
        name = st.name.lower()
        positional = [a.value for a in st.args if a.name is None]
        if name in _DATA:
            self.data_instruction(st, name, positional)
        elif name in MOVES:
            self.motion(st, name)
        elif name in ("setdo", "set", "reset"):
            on = {"set": True, "reset": False}.get(name)
            if on is None:
                if len(positional) != 2:
                    raise self.error("SetDO takes a signal and a value")
                on = self._num(self.eval(positional[1])) != 0
            if not positional:
                raise self.error(f"{st.name} takes a signal")
            self.set_output(positional[0], on, st, _text(st))
        elif name == "waittime":
            seconds = self._num(self.eval(positional[0])) if positional else 0.0
            self.stop_previous()
            self.dwells.append(Dwell(len(self.moves) - 1, seconds, self.spraying, st.line))
        elif name in ("waitdi", "waituntil", "waitdo"):
            self.stop_previous()
            if name == "waitdi" and len(positional) == 2:
                state = self.signal_state(positional[0], "dinput")
                if state != (self._num(self.eval(positional[1])) != 0):
                    self.warn(f"wait{st.line}", f"{st.name} waits for an input the cell does not set; coatsim goes on "
                                                "as if it came")
            elif name == "waituntil" and positional and not self._bool(self.eval(positional[0])):
                self.warn(f"wait{st.line}", "WaitUntil waits for a condition that is false here; coatsim goes on as if "
                                            "it came true")
        elif name == "velset":
            override, cap = (self._num(self.eval(a)) for a in positional[:2])
            self.velset = (override, cap)
        elif name in ("stop", "exit", "break", "systemstop"):
            self.stop_previous()
            raise Halt(f"{self.where()}: {st.name}")
        elif name in ("setao", "setgo", "pulsedo") and positional:
            self.set_output(positional[0], True, st, _text(st)) if name == "pulsedo" else None
            if name == "pulsedo" and self.signal_number(self._signal_name(positional[0])) == self.options.gun_signal:
                raise self.failure("PulseDO of the gun output: a pulse of the gun is not simulated")
        elif name in _INTERRUPTS:
            self.warn("interrupt", f"interrupts ({st.name}) are noted, not run: TRAP routines do not run in the twin")
        elif name in _IGNORED:
            pass
        elif name in self.routines:
            routine = self.routines[name]
            if routine.kind == "TRAP":
                raise self.error(f"{st.name} is a TRAP routine: it runs on an interrupt, not as a call")
            self.call(routine, st.args)
        elif name in _UNSIMULATED:
            where = f"{self.where()}: {st.name} skipped: the twin does not simulate it"
            self.skipped.append(where)
            self.unsimulated.append(where)
        else:
            self.skipped.append(f"{self.where()}: {st.name} skipped: no routine of that name in the files loaded")

    def late_bound(self, st: s.ProcCall) -> s.ProcCall:
        """The call ``%name% args`` as the call of the routine its string names."""
        name = self.eval(st.late)
        if not isinstance(name, str) or not name.strip():
            raise self.error("a late-bound call %...% names its routine by a string")
        return replace(st, name=name.strip(), late=None)

    def data_instruction(self, st: s.ProcCall, name: str, positional: list) -> None:
        """``Incr x``, ``Decr x``, ``Add x, v``, ``Clear x``: a num changed in place."""
        wanted = 2 if name == "add" else 1
        if len(positional) != wanted:
            raise self.error(f"{st.name} takes {wanted} argument{'s' if wanted > 1 else ''}")
        target = positional[0]
        if name == "clear":
            self._assign(target, 0.0)
            return
        step = self._num(self.eval(positional[1])) if name == "add" else 1.0
        self._assign(target, self._num(self.eval(target)) + (-step if name == "decr" else step))


def _text(st: s.ProcCall) -> str:
    from coatsim.languages.abb_rapid.printer import call_text

    return call_text(st)
