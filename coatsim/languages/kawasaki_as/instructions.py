"""The AS instruction words coatsim knows but does not give a motion meaning of their own,
by what the twin does with them (the parser accepts them; the interpreter acts by group)."""

from __future__ import annotations

# Motions coatsim cannot simulate: executing one is an error (exit 3).
UNSIMULATED_MOTION = frozenset({
    "ALIGN", "DRIVE", "ABSDRIVE", "HMOVE", "FLMOVE", "FJMOVE", "L3LMOVE", "L3C1MOVE", "L3C2MOVE", "MLJMOVE",
    "MLLMOVE", "MLC1MOVE", "MLC2MOVE", "MRLMOVE", "MRC1MOVE", "MRC2MOVE", "CVLMOVE", "CVJMOVE", "CVC1MOVE",
    "CVC2MOVE", "CVLAPPRO", "CVLDEPART", "CVHMOVE", "CVMLJMOVE", "JUMP",
})
# Grippers, clamps and spot guns: not modelled (a warning).
GRIPPER = frozenset({
    "OPEN", "OPENI", "OPENS", "CLOSE", "CLOSEI", "CLOSES", "RELAX", "RELAXI", "RELAXS", "CLAMP", "GUNON", "GUNOFF",
    "GUNONTIMER", "GUNOFFTIMER", "HSETCLAMP",
})
# Arm configuration, payload, limits, home poses: the cell model decides (a warning).
CONFIGURATION = frozenset({
    "RIGHTY", "LEFTY", "ABOVE", "BELOW", "UWRIST", "DWRIST", "WEIGHT", "SETHOME", "SETHOME2", "SET2HOME", "ULIMIT",
    "LLIMIT", "BSPEED", "FREE", "FTOOL", "LOCK", "PRIORITY", "SLOW_REPEAT", "SETTIME", "GROUP",
})
# Other programs and tasks: not run (a warning).
TASKS = frozenset({
    "PCEXECUTE", "PCABORT", "PCKILL", "PCEND", "PCCONTINUE", "PCSTEP", "PCSCAN", "MC", "EXECUTE", "ABORT", "KILL",
    "CONTINUE", "EXTCALL",
})
# Network and serial communication: not simulated; result variables get default values (a warning).
NETWORK = frozenset({
    "TCP_ACCEPT", "TCP_CLOSE", "TCP_CONNECT", "TCP_END_LISTEN", "TCP_ISLINK", "TCP_LISTEN", "TCP_RECV", "TCP_SEND",
    "TCP_STATUS", "UDP_RECVFROM", "UDP_SENDTO", "SC2RECEIVE", "SC2SEND", "SCPROTOCOL", "SCSETSIO",
})
# Operator displays and messages: no effect on the path (silent).
DISPLAY = frozenset({
    "IFPWPRINT", "IFPLABEL", "IFPTITLE", "IFPWOVERWRITE", "IFPDISP", "TPLIGHT", "OPEINFO", "OPEINFOCLR", "HELP",
})
# Interrupts, timers and other signal housekeeping: not simulated (a warning).
HOUSEKEEPING = frozenset({
    "ON", "ONI", "ONE", "IGNORE", "TIMER", "UTIMER", "RUNMASK", "SOUT", "DEFSIG", "RESET", "ERESET", "SIGPOINT",
    "TRACE", "ERRLOG",
})
COMMANDS = UNSIMULATED_MOTION | GRIPPER | CONFIGURATION | TASKS | NETWORK | DISPLAY | HOUSEKEEPING
# Commands whose text after the word is kept verbatim (it is not expression syntax).
RAW_TEXT = frozenset({"MC", "EXECUTE", "ON", "ONI", "ONE", "TIMER", "UTIMER", "PCEXECUTE", "PCABORT", "PCKILL",
                      "PCEND", "PCCONTINUE", "PCSTEP", "ABORT", "KILL", "CONTINUE", "SOUT", "DEFSIG", "EXTCALL"})
# System switches a program may set with ``NAME ON`` / ``NAME OFF``.
SWITCHES = frozenset({
    "CP", "QTOOL", "ABS.SPEED", "OX.PREOUT", "PREFETCH.SIGINS", "CHECK.HOLD", "CYCLE.STOP", "REP_ONCE", "STP_ONCE",
    "RPS", "MESSAGES", "SCREEN", "AFTER.WAIT.TMR", "CVMOVE.NOBREAK", "HOLD.STEP", "DEST_CIRINT", "SINGULAR",
})
# Teach-pendant block steps saved in program bodies.
BLOCK_STEPS = frozenset({"JOINT", "LINEAR", "CIRCULAR", "CIRCULAR1", "CIRCULAR2", "FJOINT", "FLINEAR", "XLINEAR"})
