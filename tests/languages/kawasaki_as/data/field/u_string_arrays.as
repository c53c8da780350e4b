.PROGRAM labels()
  .$names[1] = "LEFT"
  .$names[2] = "RIGHT"
  .$names[3] = "TOP"
  FOR .i = 1 TO 3
    SCASE .$names[.i] OF
      SVALUE "LEFT":
        POINT .p[.i] = SHIFT(org BY -50, 0, 0)
      SVALUE "RIGHT":
        POINT .p[.i] = SHIFT(org BY 50, 0, 0)
      ANY :
        POINT .p[.i] = SHIFT(org BY 0, 50, 0)
    END
  END
  CALL trace.part(.&p[], 3)
.END
.PROGRAM trace.part(.&rel[], .n)
  SPEED 120 MM/S ALWAYS
  JMOVE org
  LMOVE .rel[1]
  BREAK
  SIGNAL 1
  FOR .i = 2 TO .n
    LMOVE .rel[.i]
  END
  BREAK
  SIGNAL -1
.END
.TRANS
org 680 0 300 0 180 0
.END
