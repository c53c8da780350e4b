"""AS programs in the styles real cells use, written for these tests (not copied from anyone):
contour tracing by hand, machine tending, palletising, arc polishing, a drawing robot, and a
controller backup with its data sections."""

from __future__ import annotations

import math

import numpy as np


def rounded_rectangle_points(width: float = 120.0, height: float = 60.0, radius: float = 12.0,
                             step: float = 1.0) -> np.ndarray:
    """Points every ~``step`` mm around a rounded rectangle centred on the origin (closed)."""
    from coatsim.geometry.builtin_curves import rounded_rectangle

    n = int(2 * (width + height) / step)
    pts = rounded_rectangle(points=n, width=width, height=height, radius=radius)
    return pts if np.allclose(pts[0], pts[-1]) else np.vstack((pts, pts[:1]))


def user_contour(points: np.ndarray, *, z: float = 300.0, origin=(700.0, 0.0), tilt_deg: float = 0.0,
                 crlf: bool = True) -> bytes:
    """Hand-written contour tracing: lower case, step numbers, a variable for the gun output,
    CALLed gun routines, every point an LMOVE to an array element in .TRANS, a comment in a
    Windows code page. ``tilt_deg`` tilts the plane of the contour about the x axis."""
    c, s = math.cos(math.radians(tilt_deg)), math.sin(math.radians(tilt_deg))
    body = [".PROGRAM trace()", "  ; contour \xe9paisseur 0.2 mm", "  10 base null", "  tool tcp_gun",
            "  speed 150 mm/s always", "  accuracy 1 always", "  jmove #park", "  jappro c[0], 40", "  lmove c[0]",
            "  call gun_on"]
    for i in range(1, len(points)):
        body.append(f"  {100 + i} lmove c[{i}]")
    body += ["  call gun_off", "  ldepart 40", "  jmove #park", ".END",
             ".PROGRAM gun_on()", "  break", "  signal o_gun", "  twait(0.1)", ".END",
             ".PROGRAM gun_off()", "  break", "  signal -o_gun", ".END",
             ".REALS", "o_gun = 1", ".END", ".JOINTS", "#park 0 0 35 0 55 0", ".END", ".TRANS", "tcp_gun 0 0 250 0 0 0"]
    for i, (x, y) in enumerate(points):
        yy, zz = y * c, z + y * s
        a = 180.0 - tilt_deg  # tool axis along the tilted plane's normal
        body.append(f"c[{i}] {origin[0] + x:.4f} {origin[1] + yy:.4f} {zz:.4f} 90.000 {a:.4f} -90.000")
    body.append(".END")
    text = ("\r\n" if crlf else "\n").join(body) + ("\r\n" if crlf else "\n")
    return text.encode("latin-1")


MACHINE_TENDING = """\
.PROGRAM tend_cell()
  ; unload a lathe, load a blank, count parts
  .parts = 0
  HOME
  SPEED 50 ALWAYS
  ACCURACY 10 ALWAYS
  WHILE .parts < 3 DO
    SWAIT 1001, -1002          ; chuck open, door not blocked
    JAPPRO lathe_pick, 100
    OPENI
    LMOVE lathe_pick
    CLOSEI
    LDEPART 100
    JMOVE #via_table
    CALL drop_part(.parts)
    .parts = .parts + 1
    TYPE "parts done: ", .parts
  END
  HOME
.END
.PROGRAM drop_part(.n)
  POINT .slot = SHIFT(table_0 BY 60 * .n, 0, 0)
  JAPPRO .slot, 50
  LMOVE .slot
  OPENI
  LDEPART 50
.END
.TRANS
lathe_pick 650 -250 420 0 180 0
table_0 550 150 320 0 180 0
.END
.JOINTS
#via_table 30 10 40 0 40 0
.END
"""

PALLETISING = """\
.PROGRAM pallet()
  BASE TRANS(0, 0, 100, 0, 0, 0)
  SPEED 1500 MM/MIN ALWAYS
  .n = 0
  FOR .row = 0 TO 1
    FOR .col = 0 TO 2 STEP 1
      POINT .place = corner + TRANS(.col * 80, .row * 60, 0)
      JAPPRO .place, 80
      LMOVE .place
      PULSE 7, 0.2
      LDEPART 80
      .n = .n + 1
    END
  END
  CASE .n OF
    VALUE 6:
      DECOMPOSE d[1] = .place
      POINT/Z lift = .place
    ANY :
      HALT
  END
.END
.TRANS
corner 500 -100 200 0 180 0
lift 0 0 500 0 180 0
.END
"""

ARC_POLISHING = """\
.PROGRAM polish()
  tool tcp
  speed 3000 mm/min always
  accuracy 0.5 always
  jmove start
  lmove a1
  signal 3
  c1move v1
  c2move a2
  lmove a3
  c1move v2
  c2move a4
  accuracy 1 fine
  lmove a1
  break
  signal -3
  twait(1)
.END
.TRANS
tcp 0 0 250 0 0 0
start 650 -50 350 0 180 0
a1 650 -50 300 0 180 0
v1 679.289 -42.929 300 0 180 0
a2 700 -0 300 0 180 0
a3 700 50 300 0 180 0
v2 685.355 85.355 300 0 180 0
a4 650 100 300 0 180 0
.END
"""

DRAWING = """\
.PROGRAM draw_main()
  .$cmd = ""
  TCP_LISTEN .ret, 49152
  TCP_ACCEPT .sock, 49152, 10
  TCP_RECV .ret, .sock, $buf[1], .n, 5, 255
  IF .n == 0 GOTO 20
  .$cmd = $buf[1]
20 JMOVE pen_up
  LMOVE SHIFT(pen_up BY , , -20)
  SIGNAL 1
  DRAW 40, , 
  DRAW , 40, 0
  TDRAW -40, 0, 0
  DRAW 0, -40
  SIGNAL -1
  LDEPART 20
  TCP_CLOSE .ret, .sock
.END
.TRANS
pen_up 700 0 320 0 180 0
.END
"""

BACKUP = (
    ".***************************************************************\r\n"
    ".*USER IF AS               : UAS 2019/10/15 19:44\r\n"
    ".*   [Shipment setting data]\r\n"
    ".NETCONF     192.168.0.2,\"ctrl\",255.255.255.0,192.168.0.1\r\n"
    ".LANGUAGE ENGLISH\r\n"
    ".ROBOTDATA1\r\n"
    "ZROBOT.TYPE    34  30   7 1593      -24961\r\n"
    "ZULIMIT  180.0 76.0 90.0 210.0 125.0 210.0 -55525377\r\n"
    ".END\r\n"
    ".AUXDATA\r\n"
    "TOOL1  0.0 0.0 250.0 0.0 0.0 0.0\r\n"
    ".END\r\n"
    ".SYSDATA\r\n"
    "SWITCH CP ON\r\n"
    ".END\r\n"
    ".INTER_PANEL_D\r\n"
    "1,0,\"start\",2,0,0\r\n"
    ".END\r\n"
    ".SIG_COMMENT\r\n"
    "N_OX1 \"gun \xf6ffnen\"\r\n"
    ".END\r\n"
    ".PROGRAM autostart.pc() #0\r\n"
    "  SIGNAL 2001\r\n"
    "  .END\r\n"
    ".PROGRAM main()@25/11/13 12:08 #4; cell main\r\n"
    "  JMOVE home1\r\n"
    "  SIGNAL 1\r\n"
    "  LMOVE p2\r\n"
    "  SIGNAL -1\r\n"
    "   .END\r\n"
    ".TRANS\r\n"
    "home1 600.0 0.0 400.0 0.0 180.0 0.0 1200.0\r\n"
    "p2 650.0 0.0 300.0 0.0 180.0 0.0 1200.0\r\n"
    ".END\r\n"
    ".STRINGS\r\n"
    "$cell = \"Zelle 3; Halle B\"\r\n"
    ".END\r\n"
).encode("latin-1")
