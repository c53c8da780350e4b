.**************************************************************************
.*USER IF AS               : UAS 2021/03/02 07:15
.*USER IF TP               : UTP 2021/03/02 07:15
.*ARM CONTROL AS           : AAS 2021/03/02 07:15
.*   [Shipment setting data]
.**************************************************************************
.NETCONF     10.0.0.21,"SEALER2",255.255.255.0,10.0.0.1,0.0.0.0,0.0.0.0,""
.NETCONF3    1,-1,-1,-1,-1
.ROBOTDATA1
ZROBOT.TYPE    12  30   7 1593      -24961
ZSYSTEM        0   0   0   0   0   0
.END
.AUXDATA
TOOL1  0.0 0.0 205.0 0.0 0.0 0.0
.END
.SYSDATA
SWITCH CP ON
SWITCH QTOOL OFF
.END
.PROGRAM autostart.pc() ;
  PCEXECUTE 2: cnt.pc, -1
.END
.PROGRAM main() #0
  ; bead on the door frame, direction from the PLC
  BASE NULL
  TOOL nozzle
  SPEED bead.speed MM/S ALWAYS
  ACCURACY 1 ALWAYS
  JMOVE #park
  IF direction == 8 THEN
    CALL bead.left
  ELSE
    CALL bead.right
  END
  $cnt[0] = $cnt[0] + "x"
  TYPE "beads: ", $cnt[0]
  JMOVE #park
.END
.PROGRAM bead.left() #0
  LAPPRO b1, 30
  LMOVE b1
  BREAK
  SIGNAL 1
  LMOVE b2
  LMOVE b3
  LMOVE b4
  BREAK
  SIGNAL -1
  LDEPART 30
.END
.PROGRAM bead.right() #0
  LAPPRO b4, 30
  LMOVE b4
  BREAK
  SIGNAL 1
  LMOVE b3
  LMOVE b2
  LMOVE b1
  BREAK
  SIGNAL -1
  LDEPART 30
.END
.TRANS
nozzle 0.000 0.000 205.000 0.000 0.000 0.000
b1 620.000 -150.000 260.000 0.000 180.000 0.000
b2 760.000 -150.000 260.000 0.000 180.000 0.000
b3 760.000 150.000 260.000 0.000 180.000 0.000
b4 620.000 150.000 260.000 0.000 180.000 0.000
.END
.JOINTS
#park 0.000 0.000 35.000 0.000 55.000 0.000
.END
.STRINGS
$cell = "SEALER2"
.END
