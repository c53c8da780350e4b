.PROGRAM draw_sq()
  ; pen plotter: square with DRAW, frame from 3 taught points
  TOOL pen
  SPEED 100 MM/S ALWAYS
  POINT frm = FRAME(o1, x1, y1, o1)
  POINT st = frm + TRANS(20, 20, 0, 0, 180, 0)
  JAPPRO st, 30
  LMOVE st
  SIGNAL 1
  DRAW 50, ,
  DRAW , 50
  DRAW -50, 0, 0
  TDRAW 0, 50
  BREAK
  SIGNAL -1
  LDEPART 30
.END
.TRANS
pen 0 0 250 0 0 0
o1 600 -100 300 0 0 0
x1 700 -100 300 0 0 0
y1 600 0 300 0 0 0
.END
