.PROGRAM handling()
 1 SPEED 70 ALWAYS
 2 ACCURACY 10 ALWAYS
 3 JMOVE #h.home
 10 SWAIT 1003
 11 CASE part.type OF
 12  VALUE 1:
 13   POINT .drop = drop.a
 14  VALUE 2:
 15   POINT .drop = drop.b
 16  ANY :
 17   POINT .drop = drop.a
 18 END
 19 JAPPRO grab, 60
 20 LMOVE grab
 21 SIGNAL 9
 22 TWA 0.4
 23 LDEPART 60
 24 JAPPRO .drop, 60
 25 LMOVE .drop
 26 SIGNAL -9
 27 TWA 0.4
 28 LDEPART 60
 29 .cnt = .cnt + 1
 30 IF .cnt < 2 GOTO 10
 31 JMOVE #h.home
.END
.TRANS
grab 600 -200 280 0 180 0
drop.a 620 200 300 0 180 0
drop.b 720 200 300 0 180 0
.END
.JOINTS
#h.home 0 0 35 0 55 0
.END
