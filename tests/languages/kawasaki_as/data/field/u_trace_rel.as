.PROGRAM main()
  ; trace a part from poses relative to its fixture (2-D pose array in .TRANS)
  SPEED 150 MM/S ALWAYS
  ACCURACY 0.5 ALWAYS
  JMOVE #m.home
  FOR .i = 1 TO 2
    FOR .j = 1 TO 2
      POINT .p.rel[.i,.j] = p.rel[.i,.j]
    END
  END
  CALL trace.part(.&p.rel[,])
  JMOVE #m.home
.END
.PROGRAM trace.part(.&r[,])
  LMOVE fixture + .r[1,1]
  BREAK
  SIGNAL 1
  LMOVE fixture + .r[1,2]
  LMOVE fixture + .r[2,1]
  LMOVE fixture + .r[2,2]
  BREAK
  SIGNAL -1
.END
.PROGRAM main.pc()
.END
.TRANS
fixture 650 0 280 0 0 0
p.rel[1,1] -40 -40 0 0 180 0
p.rel[1,2] 40 -40 0 0 180 0
p.rel[2,1] 40 40 0 0 180 0
p.rel[2,2] -40 40 0 0 180 0
.END
.JOINTS
#m.home 0 0 35 0 55 0
.END
