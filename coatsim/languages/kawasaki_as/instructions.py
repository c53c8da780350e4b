"""The AS instruction words coatsim reads as commands (a name and its arguments), by what the
twin does with them (the parser accepts them; the interpreter acts by group; only DRIVE moves).

The lists follow the instruction index of the AS language (program instructions, the monitor
commands a program may hold, and the options' instructions: conveyor tracking, dual arm, sensing,
fieldbus, network); an instruction of the index that is missing here is a syntax error naming it.
"""

from __future__ import annotations

# Motions coatsim cannot simulate: the motion is skipped with a note (execution refuses).
UNSIMULATED_MOTION = frozenset({
    "ALIGN", "ABSDRIVE", "FLMOVE", "FJMOVE", "L3LMOVE", "L3C1MOVE", "L3C2MOVE", "MLJMOVE",
    "MLLMOVE", "MLC1MOVE", "MLC2MOVE", "MRLMOVE", "MRC1MOVE", "MRC2MOVE", "CVLMOVE", "CVJMOVE", "CVC1MOVE",
    "CVC2MOVE", "CVLAPPRO", "CVLDEPART", "CVHMOVE", "CVMLJMOVE", "CVL3LMOVE", "CVMLL3LMOVE", "MLZL3LMOVE", "JUMP",
    "SJUMP", "COOP.DRIVE.EX1", "COOP.DRIVE.EX2",
})
# Grippers, clamps and spot guns: not modelled (a note).
GRIPPER = frozenset({
    "OPEN", "OPENI", "OPENS", "CLOSE", "CLOSEI", "CLOSES", "RELAX", "RELAXI", "RELAXS", "CLAMP", "GUNON", "GUNOFF",
    "GUNONTIMER", "GUNOFFTIMER", "HSETCLAMP", "SETPICK", "SETPLACE",
})
# Arm configuration, payload, limits, home poses, tool shapes: the cell model decides (a note).
CONFIGURATION = frozenset({
    "RIGHTY", "LEFTY", "ABOVE", "BELOW", "UWRIST", "DWRIST", "WEIGHT", "SETHOME", "SETHOME2", "SET2HOME", "ULIMIT",
    "LLIMIT", "BSPEED", "FREE", "FTOOL", "LOCK", "PRIORITY", "SLOW_REPEAT", "SETTIME", "GROUP", "TOOLSHAPE",
    "SET_TOOLSHAPE", "SET_MAXTOOLSHAPENUM", "ENA_TOOLSHAPE", "CURLIM", "ALLROB_SPSET", "SLOW", "PALMODE",
    "L3ACCURACY", "L3SPEED", "L3TOOL", "L3JNT", "L3TRN", "L3ARMSLOWMODE", "L3ARMSLOWRATE", "L3ARMSLOWSET",
    "L3LINKSLOWMODE", "L3LINKSLOWRATE", "L3LINKSLOWSET", "ZAREASLOWMODE", "ZAREASLOWRATE", "ZAREASLOWSET",
    "ZINTFTOOLMDL", "ZINTFXLINK2BRAD", "ZINTFXLINK2RAD", "ZINTFXLINKRAD", "ZL3LINK2BOX", "GETLLMIT", "GETULIMIT",
})
# Other programs, tasks and monitor commands: not run (a note).
TASKS = frozenset({
    "PCEXECUTE", "PCABORT", "PCKILL", "PCEND", "PCCONTINUE", "PCSTEP", "PCSCAN", "MC", "EXECUTE", "ABORT", "KILL",
    "CONTINUE", "EXTCALL", "PRIME", "STEP", "MSTEP", "STPNEXT", "HOLD", "ALONE", "MASTER", "SLAVE", "ZALLPGKILL",
    "LOAD", "SAVE", "NLOAD", "SLOAD", "LIST", "DIRECTORY", "DELETE", "EDIT", "COPY", "RENAME", "HELP", "ID",
    "STATUS", "WHERE", "TIME", "SYSINIT", "SHUTDOWN", "ZPOWER", "ZZERO", "ZRMTSET", "ZRMTSET2", "USB_COPY",
    "USB_FDEL", "USB_FDIR", "USB_LOAD", "USB_MKDIR", "USB_RENAME", "USB_SAVE", "LANGUAGE", "BATCHK", "CHSUM",
    "ZSOFT_EXCHANGE", "ZSOFT_EXCHANGE_AUTO", "NOEXIST_SET_L", "NOEXIST_SET_R", "NOEXIST_SET_S", "MNTINFOGET",
})
# Network, serial and fieldbus communication: not simulated; result variables get default values (a note).
NETWORK = frozenset({
    "TCP_ACCEPT", "TCP_CLOSE", "TCP_CONNECT", "TCP_END_LISTEN", "TCP_ISLINK", "TCP_LISTEN", "TCP_RECV", "TCP_SEND",
    "TCP_STATUS", "UDP_RECVFROM", "UDP_SENDTO", "SC2RECEIVE", "SC2SEND", "SCPROTOCOL", "SCSETSIO", "COM",
    "FB_PORT_ASSIGN", "FB_RESET_ABCC", "FB_S_CCL", "FB_SET_WORD", "FB_SIG_ORDER", "PLCAIN", "PLCAOUT",
    "ROBNET_TCHMASTER", "ROBNETID", "ROBNETROBOT", "ROBNETSIG", "ACCEPT", "REC_ACCEPT",
})
# Operator displays and messages: no effect on the path (silent).
DISPLAY = frozenset({
    "IFPWPRINT", "IFPLABEL", "IFPTITLE", "IFPWOVERWRITE", "IFPDISP", "TPLIGHT", "OPEINFO", "OPEINFOCLR",
})
# Interrupts, timers, signal housekeeping, sensing, logging and the options' instructions (conveyor
# tracking, collision detection, force sensing, analog outputs): not simulated (a note).
HOUSEKEEPING = frozenset({
    "ON", "ONI", "ONE", "IGNORE", "TIMER", "UTIMER", "RUNMASK", "SOUT", "DEFSIG", "ERESET", "ALLERESET",
    "SIGPOINT", "TRACE", "ERRLOG", "MVWAIT", "MON_TWAIT", "SIGAPPRO", "SIGDEPART", "RSIGCORRECT", "RSIGPOINT",
    "RSIGRANGE", "CVRESETSIG_DELAY", "SCNT", "SCNTRESET", "HSENSE", "HSENSESET", "INPUT", "OUTPUT", "IO", "OPLOG",
    "LSTRACE", "RESTRACE", "SETTRACE", "STIM", "ERR_ALLROBSTOP", "INTFCHK", "IPEAKCLR", "IPEAKLOG", "INS_POWER",
    "ENC_TEMP", "ENCCHK_EMG", "ENCCHK_PON", "SETENCTEMP_THRES", "ENV_DATA", "ENV2_DATA", "ENVCHKRATE", "NCHON",
    "NCHOFF", "FFSET", "FFRESET", "FFSET_STATUS", "REFFLTSET", "REFFLTRESET", "REFFLTSET_STATUS", "SFLK", "SFLP",
    "STG_CHCOMBI", "STG_SAMPLING", "STG_START", "STG_STOP", "STRGCLR", "STRGSET", "STRGSETIO", "STRGSTART",
    "STRGSTOP", "CBSMON_EXTDISABLE", "CBSMON_EXTENABLE", "CBSMON_SETDEVICE", "COOPSTATUS", "DECMPCOLR",
    "DECMPCOLRJ", "OUTDA", "SETOUTDA", "DAOFFSET", "ADC", "CNTADC", "ZCNTUP", "ZSIGMAP", "ZSIGMAP_CLEAR",
    "ZSIGSPEC", "SETCCVSLOPE", "SETCOLTHID", "SETLCVSLOPE", "PMODSTART", "PMODEND", "PMODLIMIT", "PMODPRINTDATA",
    "PMODTXYZ", "PMODXYZ", "PMOD_LINSP", "PMOD_ROTSP", "COLINIT", "COLMVON", "COLMVOFF", "COLCALON", "COLCALOFF",
    "COLCOLDON", "COLCOLDOFF", "COLRON", "COLROFF", "COLRJON", "COLRJOFF", "COLTON", "COLTOFF", "COLTJON",
    "COLTJOFF", "CVDELAY", "CVENCSGN", "CVFLS2", "CVFMAX", "CVFNONPITCH", "CVFPH2", "CVGAIN", "CVMAXSPD",
    "CVPITCH", "CVPOS", "CVPOS2", "CVRESET", "CVSCALE", "CVSET", "CVSIMU", "CVSMAX", "CVSPEED", "CVSWITCH",
    "CVWAIT", "CVXYSIGN", "CVCOOPJT", "FHERE", "MHERE", "S_HERE",
})
# Turns every external output off (the gun with it).
OUTPUTS_OFF = frozenset({"RESET"})
# Turns one joint by an angle (DRIVE joint, angle[, speed]): a joint move, run by the interpreter.
JOINT_DRIVE = frozenset({"DRIVE"})
COMMANDS = UNSIMULATED_MOTION | GRIPPER | CONFIGURATION | TASKS | NETWORK | DISPLAY | HOUSEKEEPING | OUTPUTS_OFF | \
    JOINT_DRIVE
# Commands whose text after the word is kept verbatim (it is not expression syntax).
RAW_TEXT = frozenset({"MC", "EXECUTE", "ON", "ONI", "ONE", "TIMER", "UTIMER", "PCEXECUTE", "PCABORT", "PCKILL",
                      "PCEND", "PCCONTINUE", "PCSTEP", "ABORT", "KILL", "CONTINUE", "SOUT", "DEFSIG", "EXTCALL",
                      "LOAD", "SAVE", "LIST", "DIRECTORY", "DELETE", "EDIT", "COPY", "RENAME", "HELP", "PRIME",
                      "STEP", "HSENSESET", "MVWAIT", "SYSINIT", "USB_SAVE", "USB_LOAD"})
# System switches a program may set with ``NAME ON`` / ``NAME OFF``.
SWITCHES = frozenset({
    "CP", "QTOOL", "ABS.SPEED", "OX.PREOUT", "PREFETCH.SIGINS", "CHECK.HOLD", "CYCLE.STOP", "REP_ONCE", "STP_ONCE",
    "RPS", "MESSAGES", "SCREEN", "AFTER.WAIT.TMR", "CVMOVE.NOBREAK", "HOLD.STEP", "DEST_CIRINT", "SINGULAR",
})
# Teach-pendant block steps saved in program bodies.
BLOCK_STEPS = frozenset({"JOINT", "LINEAR", "CIRCULAR", "CIRCULAR1", "CIRCULAR2", "FJOINT", "FLINEAR", "XLINEAR"})
