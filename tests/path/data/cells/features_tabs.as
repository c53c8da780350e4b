.PROGRAM main_b ( ) ; test of features
	; tabs for indentation
	$name = "cell B"
	.$tmp = $MID($name, 1, 4) + $CHR(65)
	n = LEN(.$tmp)
	IF n <> 5 THEN
		HALT
	END
	FOR .i = 1 TO 3
		a[.i] = .i * 2.5
	END
	total = 0
	.k = 0
	WHILE .k < 3 DO
		.k = .k + 1
		total = total + a[.k]
	END
	DO
		total = total - 1
	UNTIL total <= 10
	CASE .k OF
	  VALUE 1, 2:
	    TYPE "small"
	  VALUE 3:
	    TYPE "three"
	  ANY :
	    TYPE "other"
	END
	SCASE $name OF
	  SVALUE "cell A":
	    TYPE "A"
	  SVALUE "cell B":
	    TYPE "B"
	  ANY :
	END
	CALL sub1(.k, &total)
	IF total <> 99 THEN
	   STOP
	END
	POINT p1 = TRANS(600, 0, 300, 0, 180, 0)
	POINT p2 = p1 + TRANS(50, , )
	POINT p3 = SHIFT(p2 BY 0, 50)
	DECOMPOSE v[0] = p3
	x3 = v[0]
	IF ABS(x3 - 550) > 0.001 THEN
	  HALT
	END
	SPEED 200MM/S ALWAYS
	ACCURACY 1 FINE
	JMOVE p1
	LMOVE p2
	SIGNAL 1
	LMOVE p3
	LMOVE p3 + TRANS(, -50)
	SIGNAL -1
	TWAIT(1)
	JDEPART 50
	HOME
.END
.PROGRAM sub1(.a, .b)
	.b = 99
	RETURN
.END
