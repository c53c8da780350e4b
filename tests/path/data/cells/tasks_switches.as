.PROGRAM autostart.pc()
    PCABORT 2:
    PCEXECUTE 2: watch.pc, -1 ; background task
    WAIT SWITCH(POWER)
    WAIT NOT SIG(98)
    MC EXECUTE h_main, -1
.END
.PROGRAM watch.pc ()
  ;
.END
.PROGRAM h_main ( ) ;
  ;
  ; System switches
  CP ON
  PREFETCH.SIGINS OFF
  QTOOL OFF
  REP_ONCE ON
  HOLD.STEP ON
  DISP.EXESTEP ON
  ABS.SPEED ON
  errstart.pc ON  ;
  ;
  IFPWPRINT 8, 1, 1, 5, 10 = "Robot: RS013N", "Cell 4", " "
  CALL set.vars
  .$pg = "sub" + $ENCODE (/L, 1)
  SCALL .$pg
  IF EXISTPGM("sub1") THEN
    CALL sub1
  END
  TYPE 0: "start ", run.count
  PRINT "x"
  TWAIT 0.1
  JMOVE #[0, 0, 35, 0, 55, 0]
  HERE .p0
  HERE #j0
  POINT .p1 = .p0 + TRANS (0, 0, -50)
  LMOVE .p1
  LMOVE .p1 + TRANS (20)
  BREAK
  SIGNAL out.gun
  LMOVE .p1 + TRANS (20, 100)
  SIGNAL -out.gun
  TWAIT 0.2
  JMOVE #j0
  ; absolute joint move with blank component
  LAPPRO .p1, -50
  DLYSIG -2, 0.5
  PULSE 3, 0.2
  SIGNAL 5, -6, 7
  BITS 9, 4 = 5
  .b = BITS(1001, 4)
  UTIMER @t1 = 0
  RUNMASK 10, 8
  ONI 1005 CALL stop.it
  IGNORE 1005
  HOME
.END
.PROGRAM set.vars ()
  out.gun = 1
  run.count = 0
  line.width = 210; 210; mm
.END
.PROGRAM sub1 ()
  run.count = run.count + 1
.END
.PROGRAM stop.it ()
  HALT
.END
