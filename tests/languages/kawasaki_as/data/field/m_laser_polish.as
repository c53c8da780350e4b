.Program Polish()
  ; laser polishing of a round boss - laser on output 12
  Tool Trans(0, 0, 180, 0, 0, 0)
  Speed 20 mm/s Always
  Accuracy 0.2 Always
  Jmove start
  Lmove a1
  Break
  Signal 12
  C1move v1
  C2move a2
  C1move v2
  C2move a1
  Break
  Signal -12
  Ldepart 40
  If Polish.Count > 100 Then
    Type "change lens"
  End
.End
.Trans
start 700 0 340 0 180 0
a1 700 -40 300 0 180 0
v1 740 0 300 0 180 0
a2 700 40 300 0 180 0
v2 660 0 300 0 180 0
.End
