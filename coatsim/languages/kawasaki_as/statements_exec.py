"""What each simple statement does when the interpreter reaches it."""

from __future__ import annotations

from typing import Callable, Optional

import numpy as np

from coatsim.geometry.space.pose import Pose
from coatsim.geometry.space.xyzoat import pose_from_xyzoat, xyzoat
from coatsim.languages.kawasaki_as import ast
from coatsim.languages.kawasaki_as.instructions import (
    CONFIGURATION,
    DISPLAY,
    GRIPPER,
    HOUSEKEEPING,
    JOINT_DRIVE,
    NETWORK,
    OUTPUTS_OFF,
    TASKS,
    UNSIMULATED_MOTION,
)
from coatsim.languages.kawasaki_as.io_model import FIRST_INPUT, signal_name
from coatsim.languages.kawasaki_as.machine import Machine
from coatsim.languages.kawasaki_as.unknowns import Absent, NotSimulated
from coatsim.languages.kawasaki_as.values import IDENTITY, PoseJoints


class ReturnFromProgram(Exception):
    """RETURN: back to the calling program."""


class StopProgram(Exception):
    """STOP / HALT: the run ends."""


_SILENT_SWITCHES = {"ABS.SPEED"}  # no effect at monitor speed 100 %
_COMPONENTS = {"X": (0,), "Y": (1,), "Z": (2,), "O": (3,), "A": (4,), "T": (5,), "OAT": (3, 4, 5)}


def _target(run: Machine, frame: Pose) -> Pose:
    return frame if run.base is IDENTITY else run.base @ frame


def _seconds(run: Machine, e: ast.Expr) -> float:
    value = run.eval.real(e)
    if value < 0.0:
        raise run.error("a time must be >= 0 s")
    return value


def _move(run: Machine, st: ast.Move) -> None:
    c, op = run.controller, st.op
    if op == "C2MOVE" and run.skipped_via is not None:
        via, run.skipped_via = run.skipped_via, None
        raise Absent(f"the arc's C1MOVE (line {via}) was skipped")
    if st.clamp is not None:
        run.warn("clamp", f"{op} ..., clamp: clamps are not simulated")
    if op == "HMOVE":  # (hybrid: the main axes joint-interpolated, the wrist straight; it ends at its pose)
        run.warn("hmove", "HMOVE (hybrid interpolation) is taken as a joint move to its pose")
    if op in ("JMOVE", "HMOVE") and run.eval.kind(st.target) == "joint":
        values = run.eval.joint_value(st.target)
        if isinstance(values, PoseJoints):
            if values.reference is not None:
                run.warn(f"ik:{st.line}", "JMOVE to a joint value taken from a pose with a reference: the cell's "
                         "inverse kinematics picks the configuration, not the reference")
            c.joint(_target(run, run.base.inverse() @ values.frame), st.line)
            return
        q = run.joints_rad(values)
        c.joint(run.fk(q, "JMOVE to a joint value"), st.line, joints=q)
        return
    target = _target(run, run.eval.pose(st.target))
    if op in ("JMOVE", "HMOVE"):
        c.joint(target, st.line)
    elif op in ("LMOVE", "XMOVE"):
        if op == "XMOVE":
            number = run.eval.integer(st.till, "the XMOVE ... TILL signal")
            if number != 0 and run.signals.state(abs(number)) == (number > 0, True):
                raise NotSimulated(f"XMOVE ... TILL {number}: the signal is already in that state, so the controller "
                                  "ends the move at once; coatsim does not simulate that")
            run.warn(f"xmove:{st.line}", "XMOVE ... TILL: the signal never comes in the simulation; the move runs to "
                     "its end")
        c.linear(op, target, st.line)
    elif op == "C1MOVE":
        c.arc_via(target, st.line)
    else:
        c.arc_end(target, st.line)


def _appro(run: Machine, st: ast.Appro) -> None:
    goal = _target(run, run.eval.pose(st.target))
    distance = run.eval.real(st.distance)
    back = Pose(goal.rotation, goal.translation_mm - distance * goal.rotation[:, 2])
    if st.op == "JAPPRO":
        run.controller.joint(back, st.line)
    else:
        run.controller.linear(st.op, back, st.line)


def _depart(run: Machine, st: ast.Depart) -> None:
    here = run.controller.need_current(st.op, st.line)
    distance = run.eval.real(st.distance)
    end = Pose(here.rotation, here.translation_mm - distance * here.rotation[:, 2])
    if st.op == "JDEPART":
        run.controller.joint(end, st.line)
    else:
        run.controller.linear(st.op, end, st.line)


def _draw(run: Machine, st: ast.Draw) -> None:
    here = run.controller.need_current(st.op, st.line)
    d = [0.0 if v is None else run.eval.real(v) for v in st.deltas] + [0.0] * (6 - len(st.deltas))
    if len(st.deltas) == 7 and st.deltas[6] is not None:
        raise NotSimulated(f"{st.op} with its own speed is not simulated; set SPEED before it")
    if any(v != 0.0 for v in d[3:6]):
        raise NotSimulated(f"{st.op} with a rotation is not simulated; use LMOVE to a pose")
    axes = here.rotation if st.op == "TDRAW" else run.base.rotation
    run.controller.linear(st.op, Pose(here.rotation, here.translation_mm + axes @ np.array(d[:3])), st.line)


def _home(run: Machine, st: ast.Home) -> None:
    number = 1 if st.number is None else run.eval.integer(st.number, "the HOME number")
    q = run.home_joints(number)
    run.controller.joint(run.fk(q, "HOME"), st.line, joints=q)


def _point(run: Machine, st: ast.PointAssign) -> None:
    if st.target.kind == "joint":
        if run.eval.kind(st.value) == "joint":
            run.set("joint", st.target, run.eval.joint_value(st.value))
            return
        frame = run.base @ run.eval.pose(st.value)  # (the joint value reaches this pose in the base frame)
        reference = None if st.reference is None else run.eval.joints(st.reference)
        run.set("joint", st.target, PoseJoints(frame, reference))
        return
    value = run.eval.pose(st.value)
    if st.component is not None and st.component.isdigit():
        run.warn(f"point/{st.component}", f"POINT/{st.component}: external axes are not simulated; {st.target.name} keeps "
                 "its x, y, z, o, a, t")
        old = run.scope_of(st.target).get("pose", run.key(st.target))
        run.set("pose", st.target, old if old is not None else IDENTITY)
        return
    if st.component is not None:
        old = run.scope_of(st.target).get("pose", run.key(st.target))
        parts = list(xyzoat(old if old is not None else IDENTITY))
        new = xyzoat(value)
        for i in _COMPONENTS[st.component]:
            parts[i] = new[i]
        value = pose_from_xyzoat(parts)
    run.set("pose", st.target, value)


def _decompose(run: Machine, st: ast.Decompose) -> None:
    values = run.eval.joints(st.value) if run.eval.kind(st.value) == "joint" else xyzoat(run.eval.pose(st.value))
    target = st.target
    if len(target.index) != 1:
        raise run.error("DECOMPOSE stores into a one-dimensional array element, as in a[1]")
    first = run.eval.integer(target.index[0], "the DECOMPOSE index")
    for i, v in enumerate(values):
        run.set("real", ast.Name(target.name, (ast.Num(float(first + i)),)), float(v))


def _here(run: Machine, st: ast.Here) -> None:
    if st.target.kind == "joint":
        run.set("joint", st.target, run.here_value())
    elif st.target.kind == "value":
        run.set("pose", st.target, run.here())
    else:
        raise run.error(f"HERE stores a pose or a joint value, not the string {st.target.name}")


def _signal(run: Machine, st: ast.Signal) -> None:
    for e in st.outputs:
        n = run.eval.integer(e, "a signal number")
        if n == 0:
            raise run.error("signal number 0 does not exist; expected n (on) or -n (off) with n >= 1")
        run.set_signal(abs(n), n > 0)


def _pulse(run: Machine, st: ast.Pulse) -> None:
    n = run.eval.integer(st.signal, "a signal number")
    seconds = None if st.seconds is None else _seconds(run, st.seconds)
    if n == 0:
        raise run.error(f"{st.op}: signal number 0 does not exist")
    if abs(n) == run.gun and st.op == "DLYSIG":  # (switched where the program reaches it: never dropped)
        run.warn(f"pulse:{st.line}", f"DLYSIG {n}: the delay is not timed; the gun switches here, as SIGNAL {n} would")
        run.set_signal(run.gun, n > 0)
        return
    if abs(n) == run.gun:  # (a pulse sprays for its time wherever the arm is: no switch of a motion models it)
        raise NotSimulated(_gun_pulse(run.gun, seconds))
    run.warn(f"pulse:{st.line}", f"{st.op} {n}: the delay is not simulated; the output takes its final state at once")
    if abs(n) < FIRST_INPUT:
        run.outputs.add(abs(n))
    run.signals.set(abs(n), n > 0 if st.op == "DLYSIG" else False)


def _gun_pulse(gun: int, seconds: Optional[float]) -> str:
    """Why a PULSE of the gun is not simulated (its spray is timed, not tied to a motion), and
    what to write instead."""
    return (f"PULSE of the gun (output {gun}) is not simulated: the gun would spray for {_pulse_time(seconds)} from "
            f"here, over whatever motion runs then; switch the gun with SIGNAL {gun} ... SIGNAL -{gun} around the "
            "motions it sprays")


def _pulse_time(seconds: Optional[float]) -> str:
    return "its pulse time" if seconds is None else f"{seconds:g} s"


def gun_pulse_problem(gun: int, seconds: Optional[float]) -> str:
    """The problem a PULSE of the gun leaves in the path read (the warning says why)."""
    return f"the sprayed path read lacks the {_pulse_time(seconds)} the PULSE of the gun (output {gun}) sprays"


def _bits(run: Machine, st: ast.Bits) -> None:
    start = run.eval.integer(st.start, "the first signal")
    count = run.eval.integer(st.count, "the signal count")
    if not 1 <= count <= 32 or start < 1:
        raise run.error(f"BITS {start}, {count}: expected a first signal >= 1 and a count of 1 to 32")
    value = int(run.eval.real(st.value))
    for i in range(count):
        run.set_signal(start + i, bool(value >> i & 1))


def _swait(run: Machine, st: ast.Swait) -> None:
    for e in st.signals:
        n = run.eval.integer(e, "a signal number")
        on, known = run.signals.state(abs(n))
        if not known:
            run.warn(f"swait:{abs(n)}", f"SWAIT {n}: {signal_name(abs(n))} is not given (--inputs or the scenario's "
                     "inputs); taken as satisfied")
        elif on != (n > 0):
            raise run.failure(f"SWAIT {n} is never satisfied: signal {abs(n)} is {'ON' if on else 'OFF'} and nothing "
                              "changes it in the simulation")


def _wait(run: Machine, st: ast.Wait) -> None:
    run.signals.unknown_read = False
    before = run.unknowns.reads
    if run.eval.truth(st.condition):
        return
    if run.signals.unknown_read or run.unknowns.reads != before:
        run.warn(f"wait:{st.line}", "WAIT: the condition depends on what the simulation does not know; taken as satisfied")
        return
    raise run.failure("WAIT condition is false and nothing changes it in the simulation")


def _output(run: Machine, st: ast.Output) -> None:
    run.eval.encode(st.items)
    if st.target is not None:
        kind = "string" if st.target.kind == "string" else "real"
        run.set(kind, st.target, "" if kind == "string" else 0.0)
        run.warn(f"prompt:{st.line}", f"PROMPT: no operator in the simulation; {st.target.name} = "
                 f"{'empty' if kind == 'string' else '0'}")


def _call(run: Machine, st: ast.CallProgram) -> None:
    name = st.program if isinstance(st.program, str) else run.eval.string(st.program)
    program = run.programs.get(name.lower())
    if program is None:
        raise Absent(f"no program named '{name}' is loaded (one kept on the controller?; loaded: "
                     f"{', '.join(p.name for p in run.programs.values())})")
    run.call(program, st.args)


def _stop(run: Machine, st: ast.Stop) -> None:
    if st.op == "PAUSE":
        run.warn("pause", "PAUSE: the simulation goes on at once")
        return
    run.stopped = f"{run.where()}: {st.op}"
    run.warn("stop", f"{st.op} ends the program here")
    raise StopProgram()


def _return(run: Machine, st: ast.Return) -> None:
    raise ReturnFromProgram()


def _switch(run: Machine, st: ast.Switch) -> None:
    if st.name == "CP":
        run.controller.cp = st.on
        return
    run.switches[st.name] = st.on
    if st.name == "QTOOL" and st.on:
        run.warn("qtool", "QTOOL ON takes the tool from the controller's tool table, which coatsim does not have; "
                 "the program's TOOL applies")
    elif st.name not in _SILENT_SWITCHES:
        run.warn(f"switch:{st.name}", f"switch {st.name} is not simulated")


def _network_defaults(run: Machine, st: ast.Command) -> None:
    """Result variables of a network call: status 0 (a socket id 1), nothing received."""
    names = [a for a in st.args if isinstance(a, ast.Name) and a.kind == "value"]
    if st.args and isinstance(st.args[0], ast.Name) and st.args[0].kind == "value":
        run.set("real", st.args[0], 1.0 if st.name in ("TCP_ACCEPT", "TCP_CONNECT") else 0.0)
    if st.name in ("TCP_RECV", "UDP_RECVFROM", "SC2RECEIVE"):
        run.unknowns.messages += 1  # (a loop that waits for one serves the cell: see Interpreter.jump)
        if len(st.args) > 3 and st.args[3] in names:
            run.set("real", st.args[3], 0.0)


def _drive(run: Machine, st: ast.Command) -> None:
    """DRIVE joint, angle[, speed]: a joint move turning one joint by ``angle`` deg from where
    the arm is (the speed, a % of the joint's, is the cell's)."""
    if len(st.args) not in (2, 3):
        raise run.error(f"DRIVE takes a joint number, an angle and an optional speed, found '{st.text}'")
    joint = run.eval.integer(st.args[0], "the DRIVE joint number")
    if not 1 <= joint <= 6:
        raise run.error(f"DRIVE joint {joint}: this six-axis arm has joints 1 to 6")
    angle = run.eval.real(st.args[1])
    c = run.controller
    if c.current is None and not c.moves:
        c.need_current("DRIVE", st.line)  # (before any motion: the arm stands at the cell's home)
    if c.current_joints is None:  # (the reader has the cell's forward kinematics only; the IK runs in execute)
        last = c.moves[-1].line if c.moves else st.line
        raise NotSimulated(f"DRIVE after a motion to a transformation (line {last}) is not simulated: it turns a "
                           "joint from the angles the arm has there, which only the arm's inverse kinematics tells "
                           "and the program reader does not solve; reach that pose with JMOVE to a joint value "
                           "(#...) before the DRIVE")
    q = c.current_joints.copy()
    q[joint - 1] += np.radians(angle)
    if len(st.args) == 3:
        run.warn("drive-speed", "DRIVE ..., speed: the joint's speed is the cell's")
    c.joint(run.fk(q, "DRIVE"), st.line, joints=q)


def _command(run: Machine, st: ast.Command) -> None:
    name = st.name
    if name in JOINT_DRIVE:
        _drive(run, st)
    elif name in UNSIMULATED_MOTION:
        raise NotSimulated(f"{name} moves the arm in a way coatsim does not simulate")
    elif name in OUTPUTS_OFF:
        for number in sorted(n for n, on in run.signals.states.items() if on and n < FIRST_INPUT):
            run.set_signal(number, False)
    elif name in NETWORK:
        _network_defaults(run, st)
        run.warn(f"cmd:{name}", f"{name}: network and serial I/O are not simulated; the status is 0 and nothing is "
                 "received")
    elif name in TASKS:
        run.warn(f"cmd:{name}", f"{name} {st.text}: not simulated (other programs, tasks and monitor commands are "
                 "not run)")
    elif name in GRIPPER:
        run.warn("gripper", f"{name}: grippers, clamps and spot guns are not simulated")
    elif name in CONFIGURATION:
        run.warn(f"cmd:{name}", f"{name}: not simulated (arm configuration, payload and limits come from the cell "
                 "model)")
    elif name in HOUSEKEEPING:
        run.warn(f"cmd:{name}", f"{name}: interrupts, timers, signal housekeeping and sensing are not simulated")
    elif name not in DISPLAY:
        run.warn(f"cmd:{name}", f"{name} is not simulated")


def _tool(run: Machine, st: ast.Tool) -> None:
    run.controller.set_tool(run.eval.pose(st.pose), st.line)


def _base(run: Machine, st: ast.Base) -> None:
    run.base = run.eval.pose(st.pose)


def _accel(run: Machine, st: ast.Accel) -> None:
    run.eval.real(st.value)
    run.warn("accel", f"{st.op}: the cell's acceleration limits apply, not the program's")


def _brake(run: Machine, st: ast.Brake) -> None:
    if not run.controller.at_rest:
        raise NotSimulated("BRAKE stops the motion in progress at once; coatsim cannot tell where the arm stands then")


def _block_step(run: Machine, st: ast.BlockStep) -> None:
    raise NotSimulated(f"a teach-pendant block step ({st.kind} ...) is not simulated; write it as JMOVE/LMOVE with "
                 "SPEED and ACCURACY")


def _assign(run: Machine, st: ast.Assign) -> None:
    if st.target.kind == "string":
        run.set("string", st.target, run.eval.string(st.value))
    else:
        run.set("real", st.target, run.eval.real(st.value))


HANDLERS: dict[type, Callable] = {
    ast.Assign: _assign,
    ast.PointAssign: _point,
    ast.Decompose: _decompose,
    ast.Here: _here,
    ast.Move: _move,
    ast.Appro: _appro,
    ast.Depart: _depart,
    ast.Draw: _draw,
    ast.Home: _home,
    ast.Delay: lambda run, st: run.controller.delay(_seconds(run, st.seconds), st.line),
    ast.Twait: lambda run, st: run.controller.twait(_seconds(run, st.seconds), st.line),
    ast.Speed: lambda run, st: run.controller.speed(run.eval.real(st.value), st.unit, st.always, st.line),
    ast.Accuracy: lambda run, st: run.controller.accuracy(run.eval.real(st.value), st.always, st.fine, st.line),
    ast.Accel: _accel,
    ast.Switch: _switch,
    ast.Break: lambda run, st: run.controller.brk(st.line),
    ast.Brake: _brake,
    ast.Tool: _tool,
    ast.Base: _base,
    ast.Signal: _signal,
    ast.Pulse: _pulse,
    ast.Bits: _bits,
    ast.Swait: _swait,
    ast.Wait: _wait,
    ast.Output: _output,
    ast.CallProgram: _call,
    ast.Return: _return,
    ast.Stop: _stop,
    ast.Command: _command,
    ast.BlockStep: _block_step,
}


def execute_statement(run: Machine, st: ast.Statement) -> None:
    HANDLERS[type(st)](run, st)


_NAMES = {ast.Assign: "assignment", ast.PointAssign: "POINT", ast.CallProgram: "CALL", ast.Home: "HOME",
          ast.Signal: "SIGNAL", ast.Bits: "BITS", ast.Swait: "SWAIT", ast.Wait: "WAIT", ast.Twait: "TWAIT"}


def statement_name(st: ast.Statement) -> str:
    """The instruction word of a statement, for notes."""
    for attr in ("op", "name", "kind"):
        value = getattr(st, attr, None)
        if isinstance(value, str):
            return value
    return _NAMES.get(type(st), type(st).__name__.upper())
