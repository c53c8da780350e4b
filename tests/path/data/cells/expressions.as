.PROGRAM g_main()
  ; ---- arithmetic and functions ----
  r1 = 7 MOD 3
  r2 = -7 MOD 3
  r3 = 2 ^ 10
  r4 = INT(-2.7)
  r5 = ABS(-3) + SQRT(16)
  r6 = ATAN2(1, 1)
  r7 = SIN(30) + COS(60)
  r8 = MAXVAL(3, 9, 2) - MINVAL(3, 9, 2)
  r9 = 5 BAND 3
  r10 = 5 BOR 3
  r11 = NOT TRUE
  r12 = (1 < 2) AND (3 >= 3)
  r13 = 1 + 2 * 3 - 4 / 2
  r14 = -2 ^ 2
  r15 = 10 / 4
  r16 = ^HFF + ^B101
  r17 = 3 == 3
  r18 = ON + OFF
  r19 = 2 * -3
  r20 = 1 <> 2
  r21 = 5 XOR 3
  r22 = 1.5E2
  r23 = .5 + 1.
  ; ---- strings ----
  $a = "Hello"
  $b = $a + ", " + "world"
  r30 = LEN($b)
  $c = $MID($b, 8, 5)
  $d = $LEFT($b, 3) + $RIGHT($b, 2)
  $e = $ENCODE(/D, 42)
  $e2 = $ENCODE(/F6.2, 3.14159)
  $e3 = $ENCODE("x=", 1.5, " y=", -2)
  $f = "12.5;7"
  $g = $DECODE($f, ";", 0)
  $h = $DECODE($f, ";", 1)
  $i = $DECODE($f, ";", 0)
  r31 = VAL($f)
  r32 = VAL("3.5")
  r33 = ASC("A")
  $j = $CHR(66)
  r34 = INSTR($b, "world")
  $k = $SPACE(3) + "|"
  r35 = $a == "Hello"
  r36 = $a <> "hello"
  ; ---- arrays ----
  FOR i = 0 TO 4
    sq[i] = i * i
  END
  mat[1, 2] = 12
  mat[2,1] = 21
  r40 = sq[3] + mat[1,2] + mat[2, 1]
  $names[0] = "a"
  $names[1] = $names[0] + "b"
  ; ---- while / do / case ----
  cnt = 0
  WHILE cnt < 10 DO
    cnt = cnt + 3
  END
  DO
    cnt = cnt - 1
  UNTIL cnt < 5
  CASE cnt OF
    VALUE 1, 2, 3:
      which = 1
    VALUE 4:
      which = 4
    ANY :
      which = -1
  END
  .loc = 5
  CALL addone(.loc, &glob_out)
  r50 = .loc
  CALL swap(&sq[1], &sq[2])
  IF r1 == 1 GOTO 100
  r60 = 999
100 r61 = 1
  IF r61 THEN
    r62 = 1
  ELSE
    r62 = 2
  END
.END
.PROGRAM addone(.x, .y)
  .x = .x + 1
  .y = .x * 10
.END
.PROGRAM swap(.a, .b)
  .t = .a
  .a = .b
  .b = .t
.END
