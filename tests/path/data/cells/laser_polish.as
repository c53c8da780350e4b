.PROGRAM laser_polish()   ; laser polishing of a round boss
   ; ---- settings ----
   BASE NULL
   TOOL laser_tcp
   SPEED 200MM/S ALWAYS
   ACCURACY 1 FINE
   ACCEL 80 ALWAYS
   DECEL 80 ALWAYS
   HOME
   JAPPRO ring_a, 50
   LMOVE ring_a
   BREAK
   SIGNAL laser_on
   TWAIT(0.2)
   ; full circle as two half circles
   C1MOVE ring_b
   C2MOVE ring_c
   C1MOVE ring_d
   C2MOVE ring_a
   ; second pass, smaller
   LMOVE inner_a
   C1MOVE inner_b
   C2MOVE inner_c
   C1MOVE inner_d
   C2MOVE inner_a
   BREAK
   SIGNAL -laser_on
   LDEPART 50
   HOME
.END
.REALS
laser_on = 1
.END
.TRANS
laser_tcp 0.0 0.0 250.0 0.0 0.0 0.0
ring_a 700.0 -40.0 300.0 90.0 180.0 -90.0
ring_b 740.0 0.0 300.0 90.0 180.0 -90.0
ring_c 700.0 40.0 300.0 90.0 180.0 -90.0
ring_d 660.0 0.0 300.0 90.0 180.0 -90.0
inner_a 700.0 -20.0 300.0 90.0 180.0 -90.0
inner_b 720.0 0.0 300.0 90.0 180.0 -90.0
inner_c 700.0 20.0 300.0 90.0 180.0 -90.0
inner_d 680.0 0.0 300.0 90.0 180.0 -90.0
.END
