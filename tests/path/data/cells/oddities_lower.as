.PROGRAM i_main() #0; #0; #0; ; main of cell
	; tab indented, lower case, real-world oddities
	call lib.init_
	if existreal("cyc.count") == 0 then
		cyc.count = 0
	end
10
	cyc.count = cyc.count + 1
	if (switch(repeat) == true) and (switch(cs) == false) then
		signal 20
	end
	IF SWITCH(CS )==ON THEN
	  SIGNAL -20
	END
	IF INSTR ($ids, ",")
	  .id = VAL ($DECODE ($ids, ",", 0))
	ELSE
	  .id = VAL ($ids)
	END
	if task(1) == 2 then
		signal 21
	end
	SIGNAL -ox_out[2],ox_ret[2]
	IF SIG(-ox_out[2]) AND SIG(ox_ret[2]) GOTO end
	WHILE (1) DO
	  GOTO end
	END
end:
	IF cyc.count < 3 GOTO 10
	TWAIT ascycle
	TYPE 0: .id, cyc.count
	JMOVE #put.outpal
	LMOVE put.outpal + TRANS (50)
	LMOVE put.outpal + TRANS (, , 50)
	CALL addpoint.pc ("3;4", 1)
	LMOVE hockey[1]
	BREAK
	SIGNAL 1
	LMOVE put.outpal
	BREAK
	SIGNAL -1
.END
.PROGRAM lib.init_() ; no params
	ox_out[2] = 31
	ox_ret[2] = 32
	ascycle = 0.1
	$ids = "17,4"
.END
.PROGRAM addpoint.pc (.$str,.index) ; 
  ;
  .$temp2 = $DECODE (.$str, ";")
  .dx = (100 - VAL (.$temp2))
  .$temp2 = $DECODE (.$str, ";",1)
  .dy = VAL (.$str)
  POINT hockey[.index] = put.outpal + TRANS (.dx, .dy)
  TYPE 0: .dx, .dy
  ;
.END
.PROGRAM Comment___ () ; Comments for IDE. Do not use.
	; @@@ PROJECT @@@
	; @@@ HISTORY @@@
.END
.JOINTS
#put.outpal 0.0 10.0 30.0 0.0 50.0 0.0
.END
.TRANS
put.outpal 650.0 0.0 300.0 0.0 180.0 0.0
.END
