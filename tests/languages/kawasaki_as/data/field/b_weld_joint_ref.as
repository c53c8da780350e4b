.*  saved by controller
.PROGRAM seam() #0
  TOOL torch
  SPEED 30 MM/S ALWAYS
  ACCURACY 0.5 ALWAYS
  POINT .app = SHIFT(s1 BY 0, 0, 50)
  POINT .#app = .app, #cfg
  JMOVE .#app
  LMOVE s1
  BREAK
  SIGNAL 1
  LMOVE s2
  LMOVE s3
  BREAK
  SIGNAL -1
  LDEPART 50
  POINT #back = s3, #cfg
  JMOVE #back
.END
.TRANS
torch 0.0 0.0 300.0 0.0 0.0 0.0
s1 650.0 -80.0 260.0 0.0 180.0 0.0
s2 700.0 0.0 260.0 0.0 180.0 0.0
s3 650.0 80.0 260.0 0.0 180.0 0.0
.END
.JOINTS
#cfg 0.0 10.0 40.0 0.0 50.0 0.0
.END
