"""KRL motions: ``PTP``, ``LIN``, ``CIRC aux, end`` (``CA`` not simulated), ``LIN_REL``/``PTP_REL``
(in the base's axes, or the tool's with ``#TOOL``: KUKA System Software 8, "LIN_REL"),
each in ``$BASE`` with ``$TOOL``, a target's missing components the current position's; speed
``$VEL.CP`` (m/s); approximation ``C_DIS`` within ``$APO.CDIS`` (``C_VEL``, ``C_ORI``, ``C_PTP``
modelled as ``C_DIS``, with a warning); ``BAS(#…)`` calls (an inline form's ``FDAT_ACT``
/``LDAT_ACT``/``PDAT_ACT`` give its tool, base and approximation distance); ``TRIGGER WHEN DISTANCE`` switches.
The interpreter's Motions part (see :mod:`.interpreter`)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from coatsim.geometry.space.pose import Pose
from coatsim.languages.kuka_krl import values as v
from coatsim.languages.kuka_krl.evaluate import Unknown
from coatsim.languages.kuka_krl.parser import Line, split_commas, statement_text
from coatsim.languages.script import nodes as n
from coatsim.languages.script.tokens import NAME
from coatsim.path.arcs import via_on_turn
from coatsim.path.reading import MoveSource
from coatsim.path.toolpath import CircularMove, JointMove, LinearMove, MotionSettings

DEFAULT_VEL_CP_M_S = 2.0  # $VEL.CP after BAS(#INITMOV) (DEF_VEL_CP of a standard $config.dat) ⚠
_APPROX = ("C_DIS", "C_VEL", "C_ORI", "C_PTP")
MOTION_DATA = ("FDAT_ACT", "LDAT_ACT", "PDAT_ACT")  # the data an inline form hands to BAS


class Motions:
    """Motions and their settings; the interpreter provides ``system``, ``moves``, ``sources``,
    ``move_frames``, ``tcp``, ``position``, ``tool``, ``spraying``, ``pending``, ``source``,
    ``routine``, ``expr``, ``eval``, ``lookup``, ``assign``, ``switch``, ``warn``, ``error`` and
    ``failure``."""

    def trigger(self, ln: Line) -> None:
        words = [t.text.upper() for t in ln.tokens]
        if "DISTANCE" not in words or "DO" not in words:
            self.warn("trigger", "TRIGGER WHEN PATH ...: a switch at a path distance is not simulated")
            return
        k = words.index("DISTANCE")
        distance = ln.tokens[k + 2].text if k + 2 < len(ln.tokens) else "0"
        if "DELAY" in words:
            delay = ln.tokens[words.index("DELAY") + 2].text
            if float(delay) != 0.0:
                self.warn("delay", f"TRIGGER ... DELAY={delay}: the delay is not simulated")
        action = list(ln.tokens[words.index("DO") + 1:])
        if "PRIO" in [t.text.upper() for t in action]:
            action = action[:[t.text.upper() for t in action].index("PRIO")]
        eq = next((k for k, t in enumerate(action) if t.text == "="), None)
        target = self.expr(action[:eq]) if eq else None
        if isinstance(target, n.Index) and isinstance(target.base, n.Name) and target.base.name.upper() == "$OUT":
            number = int(self._num(self.eval(target.index[0])))
            on = bool(self.eval(self.expr(action[eq + 1:])))
            self.switch(number, on, statement_text(ln.tokens), "next" if distance == "0" else "after")
        else:
            self.warn("trigger-action", "TRIGGER ... DO: only $OUT switches are simulated")

    def bas(self, ln: Line) -> None:
        """``BAS(#…, value)``: the calls of the BAS package a program and its inline forms make."""
        call = self.expr(ln.tokens)
        args = [a.value for a in call.args] if isinstance(call, n.Call) else []
        what = args[0].name.upper() if args and isinstance(args[0], n.Name) else ""
        value = self.eval(args[1]) if len(args) > 1 else None
        if what in ("#TOOL", "#BASE"):
            self.assign(n.Name(f"${what[1:]}", ln.line), self.frame_number(what[1:], int(value)))
        elif what in ("#VEL_CP", "#CP_PARAMS", "#PTP_PARAMS", "#FRAMES"):
            if what in ("#VEL_CP", "#CP_PARAMS") and value is not None:
                self.system["$VEL"].fields["CP"] = float(value)
            if what in ("#CP_PARAMS", "#PTP_PARAMS"):
                self.motion_data("LDAT_ACT" if what == "#CP_PARAMS" else "PDAT_ACT",
                                 "CDIS" if what == "#CP_PARAMS" else "CPTP")
            if what != "#VEL_CP":
                self.inline_frames()
        elif what == "#INITMOV":
            self.system["$VEL"].fields["CP"] = DEFAULT_VEL_CP_M_S

    def frame_number(self, kind: str, number: int) -> v.Struct:
        """Tool or base ``number`` of the robot's tables: 0 is the flange or the world ($NULLFRAME)."""
        return v.default("FRAME") if number == 0 else self.lookup(f"{kind}_DATA[{number}]")

    def motion_data(self, name: str, apo: str) -> None:
        """An inline form's LDAT/PDAT: its approximation distance becomes $APO's (BAS package)."""
        data = self.system.get(name)
        if isinstance(data, v.Struct) and "APO_DIST" in data.fields:
            self.system["$APO"].fields[apo] = float(data.fields["APO_DIST"])

    def motion_data_set(self, key: str, tokens) -> None:
        """``FDAT_ACT = FP1``, ``LDAT_ACT = LCPDAT1``, ``PDAT_ACT = PDEFAULT``: an inline form's data,
        used by the BAS call after it. A value the files do not give (``$config.dat``'s defaults)
        is listed; an unknown LDAT/PDAT keeps the approximation distance in force (said in a
        warning), an unknown FDAT skips the BAS call that needs its tool and base."""
        try:
            self.system[key] = self.eval(self.expr(tokens))
        except Unknown as unknown:
            self.unknown.read(unknown.name, self.where(), unknown.name.lower())
            self.system[key] = None if key != "FDAT_ACT" else unknown.name
            if key != "FDAT_ACT":
                self.warn(f"motion-data-{key}", f"{key} = {unknown.name}: its approximation distance is not in the "
                                                "files loaded; the one in force is kept")

    def inline_frames(self) -> None:
        """An inline form's FDAT: its tool and base numbers become $TOOL and $BASE (BAS #FRAMES)."""
        fdat = self.system.get("FDAT_ACT")
        if fdat is None:
            return
        if not isinstance(fdat, v.Struct):  # $config.dat's FHOME, say: a motion in its frames is skipped
            self.frames_unknown = fdat if isinstance(fdat, str) else "FDAT_ACT"
            self.frames_given = set()
            return
        for kind in ("TOOL", "BASE"):
            if f"{kind}_NO" in fdat.fields:
                try:
                    frame = self.frame_number(kind, int(fdat.fields[f"{kind}_NO"]))
                except Unknown as unknown:
                    self.frames_unknown = unknown.name
                    raise
                self.assign(n.Name(f"${kind}", self.line), frame)
        self.frames_unknown = ""

    def _axis_target(self, axes: v.Struct, base: Pose) -> tuple[Pose, v.Struct, np.ndarray]:
        """``PTP {A1 …, A6 …}`` (AXIS/E6AXIS, degrees): the TCP, its position and the joints."""
        names = [f"A{k}" for k in range(1, 7)]
        if any(a not in axes.fields for a in names):
            raise self.error("PTP to axis values needs A1 to A6")
        if self.options.kinematics is None:
            raise self.error("PTP to axis values needs the cell's kinematics to know where the tool goes")
        joints = np.radians([float(axes.fields[a]) for a in names])
        end = self.options.kinematics.forward(joints, self.tool)
        return end, v.frame_of(base.inverse() @ end, "E6POS", self.position), joints

    def _home_start(self, word: str) -> Pose:
        """Where a LIN or CIRC first motion starts: the cell's home, where the twin's arm stands
        when the program starts (a controller runs its first motion as the BCO run to a full
        position, normally a PTP; without the cell the start is unknown)."""
        kin = self.options.kinematics
        if kin is None:
            raise self.failure(f"{word} is the first motion: the robot's position before it is unknown; start with PTP")
        self.warn("first-motion", f"{word} is the first motion: it starts from the cell's home, where the twin's arm "
                  "stands when the program starts (a controller's BCO run is normally a PTP)")
        return kin.forward(kin.home(1), self.tool)

    def _stop_previous(self) -> None:
        if self.moves and not self.moves[-1].settings.stop_at_end:
            last = self.moves[-1]
            self.moves[-1] = replace(last, settings=replace(last.settings, stop_at_end=True))

    def _target(self, tokens: list) -> v.Struct:
        e = self.expr(tokens)
        return self._merged(self._complete(tokens, e, self.eval(e)))

    def _complete(self, tokens: list, e: n.Expr, value):
        """``value`` once sure a position variable used as a target has X to C: the controller stops
        on one declared without a value and only partly assigned since, where an aggregate written
        in the motion takes its missing components from the current position."""
        if isinstance(value, v.Struct) and not _is_axes(value) and not isinstance(e, n.Aggregate):
            missing = [f for f in v.FRAME_FIELDS if f not in value.fields]
            if missing:
                raise self.error(f"the target {statement_text(tokens)} has no {', '.join(missing)}: a position "
                                 "declared without a value has only the components assigned to it since")
        return value

    def _merged(self, value) -> v.Struct:
        if not isinstance(value, v.Struct):
            raise self.error("a motion's target must be a position ({X .., Y .., ...} or a POS/E6POS/FRAME)")
        if self.position is not None:  # missing components: the current position's
            merged = self.position.copy()
            merged.fields.update(value.fields)
            merged.type = value.type or merged.type
            return merged
        return value

    def _relative(self, base: Pose, step: Pose, relative_to: str) -> Pose:
        """The target of ``LIN_REL``/``PTP_REL step``: in the base's axes (``#BASE``, the default:
        the step's rotation about the TCP in the base's axes) or the tool's (``#TOOL``)."""
        here = base.inverse() @ self.tcp if self.position is None else v.pose_of(self.position)
        if relative_to == "#TOOL":
            return base @ (here @ step)
        return base @ Pose(step.rotation @ here.rotation, here.translation_mm + step.translation_mm)

    def _targets(self, word: str, parts: list, base: Pose, relative_to: str) -> tuple:
        """A motion's end (base frame), its position value, its auxiliary point (CIRC) and its
        joints (PTP to axis values)."""
        first = self.expr(parts[0]) if word != "CIRC" and len(parts) == 1 else None
        raw = self.eval(first) if first is not None else None
        if first is not None and not word.endswith("_REL"):
            self._complete(parts[0], first, raw)
        joints = None
        if self.frames_unknown and not _is_axes(raw):
            raise Unknown(self.frames_unknown)
        if word == "PTP" and _is_axes(raw):
            end, end_s, joints = self._axis_target(raw, base)
            via = None
        elif word == "CIRC":
            if len(parts) != 2:
                raise self.error("CIRC takes an auxiliary point and an end point")
            via_s, end_s = self._target(parts[0]), self._target(parts[1])
            via, end = base @ v.pose_of(via_s), base @ v.pose_of(end_s)
        else:
            if len(parts) != 1:
                raise self.error(f"{word} takes one target")
            end_s = raw if word.endswith("_REL") else self._merged(raw)
            if word.endswith("_REL"):
                if self.tcp is None:
                    raise self.failure(f"{word} before any motion: the position it is relative to is unknown")
                end = self._relative(base, v.pose_of(end_s), relative_to)
                end_s = v.frame_of(base.inverse() @ end, "E6POS", self.position)
            else:
                end = base @ v.pose_of(end_s)
            via = None
        return end, end_s, via, joints

    def motion(self, ln: Line) -> None:
        toks = list(ln.tokens)
        word = ln.word
        approx = ""
        relative_to = toks.pop().text.upper() if toks[-1].kind == NAME and \
            toks[-1].text.upper() in ("#BASE", "#TOOL") else "#BASE"
        while toks[-1].kind == NAME and toks[-1].text.upper() in _APPROX:  # an inline form writes C_DIS C_DIS
            approx = toks.pop().text.upper()
        parts = split_commas(toks[1:])
        if word == "CIRC":
            parts = [p for p in parts if not (p and p[0].text.upper() == "CA")]
            if len(split_commas(toks[1:])) > len(parts):
                self.warn("ca", "CIRC ... CA: the circular angle is not simulated; the arc ends at its end point")
        if word in ("PTP", "PTP_REL") and any(p and p[0].text.upper() == "C_PTP" for p in parts):
            approx = "C_PTP"
        base = v.pose_of(self.system["$BASE"])
        end, end_s, via, joints = self._targets(word, parts, base, relative_to)
        if approx in ("C_VEL", "C_ORI", "C_PTP"):
            self.warn("approx", f"{approx} is modelled as C_DIS with $APO.CDIS")
        cdis = float(self.system["$APO"].fields.get("CDIS", 0.0))
        blended = bool(approx) and cdis > 0
        speed = float(self.system["$VEL"].fields.get("CP", DEFAULT_VEL_CP_M_S)) * 1000.0
        if not speed > 0:
            raise self.error(f"$VEL.CP = {speed / 1000:g} m/s: must be > 0")
        settings = MotionSettings(speed, cdis if blended else 0.0, blended, not blended, self.tool)
        if word.startswith("PTP"):
            move = JointMove(self.tcp, end, settings, self.spraying, ln.line, joints_rad=joints)
        else:
            start = self.tcp if self.tcp is not None else self._home_start(word)
            move = (CircularMove(start, via_on_turn(start, via, end), end, settings, self.spraying, ln.line)
                    if via is not None
                    else LinearMove(start, end, settings, self.spraying, ln.line))
        self.moves.append(move)
        self.sources.append(MoveSource(self.source, self.routine, ln.line, ln.line))
        self.move_frames.append(base)
        self.tcp, self.position = end, end_s
        still = []
        for left, on in self.pending:
            if left == 0:
                self.spraying = on
            else:
                still.append((left - 1, on))
        self.pending = still


def _is_axes(value) -> bool:
    """An AXIS/E6AXIS value: axis angles A1…, no X."""
    return isinstance(value, v.Struct) and (value.type in ("AXIS", "E6AXIS") or
                                            ("A1" in value.fields and "X" not in value.fields))
