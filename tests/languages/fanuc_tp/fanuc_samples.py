"""Builders of .LS text for the Fanuc tests."""

from __future__ import annotations

from typing import Mapping, Sequence

ATTR = """/ATTR
OWNER\t\t= MNEDITOR;
COMMENT\t\t= "test";
PROG_SIZE\t= 1234;
CREATE\t\t= DATE 21-03-04  TIME 10:11:12;
MODIFIED\t= DATE 21-03-04  TIME 10:11:12;
FILE_NAME\t= ;
VERSION\t\t= 0;
LINE_COUNT\t= 0;
MEMORY_SIZE\t= 1500;
PROTECT\t\t= READ_WRITE;
TCD:  STACK_SIZE\t= 0,
      TASK_PRIORITY\t= 50,
      TIME_SLICE\t= 0,
      BUSY_LAMP_OFF\t= 0,
      ABORT_REQUEST\t= 0,
      PAUSE_REQUEST\t= 0;
DEFAULT_GROUP\t= 1,*,*,*,*;
CONTROL_CODE\t= 00000000 00000000;"""


def position(index: int, values: Sequence[float], uf: int = 0, ut: int = 0) -> str:
    x, y, z, w, p, r = values
    return (f"P[{index}]{{\n   GP1:\n\tUF : {uf}, UT : {ut},\t\tCONFIG : 'N U T, 0, 0, 0',\n"
            f"\tX = {x:10.3f}  mm,\tY = {y:10.3f}  mm,\tZ = {z:10.3f}  mm,\n"
            f"\tW = {w:10.3f} deg,\tP = {p:10.3f} deg,\tR = {r:10.3f} deg\n}};")


def ls(body: Sequence[str], positions: Mapping[int, Sequence[float]] = (), name: str = "MAIN", uf: int = 0,
       ut: int = 0) -> str:
    """An .LS program: numbered instructions ``body`` (each without its ';'), Cartesian positions."""
    lines = [f"/PROG  {name}", ATTR, "/MN"]
    for k, text in enumerate(body, start=1):
        motion = text[0] if text[:2] in ("J ", "L ", "C ", "A ") else " "
        lines.append(f"{k:4d}:{motion} {text[2:] if motion != ' ' else text} ;")
    lines.append("/POS")
    lines += [position(i, v, uf, ut) for i, v in dict(positions).items()]
    lines.append("/END")
    return "\n".join(lines) + "\n"


DOWN = (180.0, 0.0, 0.0)  # W P R of a tool pointing down
