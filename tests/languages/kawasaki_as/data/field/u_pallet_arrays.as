.PROGRAM pallet() ;palletising, layers from the HMI
  BASE NULL
  SPEED 80 ALWAYS
  ACCURACY 5 ALWAYS
  JMOVE #ready
  FOR .l = 1 TO layers
    CALL calc.layer(.l, .&pos[,])
    FOR .k = 1 TO 4
      JAPPRO .pos[.l, .k], 100
      LMOVE .pos[.l, .k]
      BREAK
      SIGNAL -5
      TWAIT 0.2
      LDEPART 100
      JMOVE infeed
      BREAK
      SIGNAL 5
      TWAIT 0.2
    END
  END
  JMOVE #ready
.END
.PROGRAM calc.layer(.n, .&p[,])
  FOR .k = 1 TO 4
    POINT .p[.n, .k] = SHIFT(corner BY ((.k - 1) MOD 2) * 120, INT((.k - 1) / 2) * 90, (.n - 1) * 60)
  END
.END
.TRANS
corner 560 -120 220 0 180 0
infeed 650 250 320 0 180 0
.END
.JOINTS
#ready 0 0 35 0 55 0
.END
