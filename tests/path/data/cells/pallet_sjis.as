.PROGRAM pal_main() #12345 ; パレタイズ メイン
; ************************************
; * ﾊﾟﾚﾀｲｽﾞ  2 x 3                     *
; ************************************
1   BASE NULL
2   TOOL gripper
3   SPEED 80 ALWAYS
4   ACCURACY 5 ALWAYS
5   HOME
6   .cnt=0
7   .max = 6
start:
8   IF .cnt>=.max GOTO done
9   .row = INT(.cnt/3)
10  .col = .cnt MOD 3
11  POINT .tgt = SHIFT(pal_org BY .col*100, .row*120, )
12  JAPPRO pick, 80
13  LMOVE pick
14  CALL grip(ON)
15  LDEPART 80
16  JAPPRO .tgt, 100
17  SPEED 30
18  LMOVE .tgt
19  CALL grip(OFF)
20  LDEPART 100
21  .cnt = .cnt+1
22  GOTO start
done:
23  HOME
24  TYPE "終了 ", .cnt
.END
.PROGRAM grip(.on)
  IF .on THEN
    SIGNAL 9,-10   ; 閉
  ELSE
    SIGNAL -9,10   ; 開
  END
  TWAIT 0.3
.END
.TRANS
gripper 0.000 0.000 180.000 0.000 0.000 0.000
pick 500.000 -300.000 250.000 0.000 180.000 0.000
pal_org 450.000 100.000 200.000 0.000 180.000 0.000
.END
