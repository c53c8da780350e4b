.PROGRAM count.parts()
  JMOVE #a
  FOR .i = 1 TO 5
    TYPE .i
  TWAIT 1
.END
.JOINTS
#a 0 0 35 0 55 0
.END
