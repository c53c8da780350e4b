.PROGRAM roundrect()
  ; coatsim polysegment program: 8 segments (4 lines, 4 arcs), tolerance 0.1 mm
  ; coatsim: variant=polysegment
  ; coatsim: source=builtin:roundrect
  ; coatsim: tolerance_mm=0.1
  ; coatsim: curve_length_mm=442.83185307
  ; coatsim: lead_in_mm=30
  ; coatsim: lead_out_mm=30
  ; coatsim: standoff_mm=100
  ; coatsim: speed_mm_s=500
  ; coatsim: accuracy_mm=1
  ; coatsim: gun_signal=1
  ; coatsim: frame=700,0,200,0,0,0
  ; coatsim: closed=yes
  ; coatsim: sprayed=curve
  ; coatsim: n_segments=8
  ; coatsim: n_lines=4
  ; coatsim: n_arcs=4
  ; coatsim: speed_limits=none
  BASE NULL                    ; poses are in the robot base frame
  TOOL TRANS(0.00000000,0.00000000,250.00000000,0.000000,0.000000,0.000000) ; spray gun TCP
  SPEED 500 MM/S ALWAYS
  ACCURACY 1 ALWAYS
  CP ON                        ; blend
  JAPPRO p0000, 50             ; above the start
  LMOVE p0000                  ; down to the stand-off
  BREAK                        ; at rest at the start of the lead-in
  LMOVE p0001                  ; lead-in
  LMOVE p0002                  ; segment 1
  SIGNAL 1                     ; gun on as the move above starts (on the fly)
  C1MOVE p0003                 ; segment 2, arc via
  C2MOVE p0004                 ; arc end
  LMOVE p0005                  ; segment 3
  C1MOVE p0006                 ; segment 4, arc via
  C2MOVE p0007                 ; arc end
  LMOVE p0008                  ; segment 5
  C1MOVE p0009                 ; segment 6, arc via
  C2MOVE p0010                 ; arc end
  LMOVE p0011                  ; segment 7
  C1MOVE p0012                 ; segment 8, arc via
  C2MOVE p0013                 ; arc end
  LMOVE p0014                  ; lead-out
  SIGNAL -1                    ; gun off as the move above starts (on the fly)
  BREAK                        ; at rest at the end of the path
  LDEPART 50                   ; back along the tool axis
.END
.TRANS
p0000 605.00000000 -40.00000000 300.00000000 0.000000 180.000000 0.000000
p0001 635.00000000 -40.00000000 300.00000000 0.000000 180.000000 0.000000
p0002 765.00000000 -40.00000000 300.00000000 0.000000 180.000000 0.000000
p0003 772.07106781 -37.07106781 300.00000000 0.000000 180.000000 0.000000
p0004 775.00000000 -30.00000000 300.00000000 0.000000 180.000000 0.000000
p0005 775.00000000 30.00000000 300.00000000 0.000000 180.000000 0.000000
p0006 772.07106781 37.07106781 300.00000000 0.000000 180.000000 0.000000
p0007 765.00000000 40.00000000 300.00000000 0.000000 180.000000 0.000000
p0008 635.00000000 40.00000000 300.00000000 0.000000 180.000000 0.000000
p0009 627.92893219 37.07106781 300.00000000 0.000000 180.000000 0.000000
p0010 625.00000000 30.00000000 300.00000000 0.000000 180.000000 0.000000
p0011 625.00000000 -30.00000000 300.00000000 0.000000 180.000000 0.000000
p0012 627.92893219 -37.07106781 300.00000000 0.000000 180.000000 0.000000
p0013 635.00000000 -40.00000000 300.00000000 0.000000 180.000000 0.000000
p0014 665.00000000 -40.00000000 300.00000000 0.000000 180.000000 0.000000
.END
