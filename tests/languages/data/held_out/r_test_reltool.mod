MODULE MainModule
	! Part family program - variant chosen from the PLC (gi_variant)
	TASK PERS tooldata tGun2:=[TRUE,[[0,0,240],[1,0,0,0]],[2,[0,0,100],[1,0,0,0],0,0,0]];
	CONST robtarget pHome:=[[700,0,450],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
	CONST robtarget pCentre:=[[700,0,300],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
	PERS num nVariant:=2;
	VAR num nRadius:=40;
	CONST speeddata vCoat:=[220,500,5000,1000];
	CONST zonedata zCoat:=[FALSE,1.5,3,3,0.3,3,0.3];

	PROC main()
		MoveJ pHome,v1000,fine,tGun2;
		TEST nVariant
		CASE 1:
			%"Ring"%;
		CASE 2,3:
			%"Ring_" + NumToStr(nVariant,0)%;
		DEFAULT:
			TPWrite "unknown variant";
			Stop;
		ENDTEST
		MoveJ pHome,v1000,fine,tGun2;
	ENDPROC

	PROC Ring()
		Circle nRadius;
	ENDPROC

	PROC Ring_2()
		Circle nRadius/2;
		Circle nRadius;
	ENDPROC

	PROC Ring_3()
		Circle nRadius*1.5;
	ENDPROC

	PROC Circle(num r)
		MoveL RelTool(pCentre,r,0,-30),vCoat,fine,tGun2;
		MoveL RelTool(pCentre,r,0,0),vCoat,fine,tGun2;
		SetDO do_Gun,1;
		MoveC RelTool(pCentre,0,r,0),RelTool(pCentre,-r,0,0),vCoat,zCoat,tGun2;
		MoveC RelTool(pCentre,0,-r,0),RelTool(pCentre,r,0,0),vCoat,fine,tGun2;
		SetDO do_Gun,0;
		MoveL RelTool(pCentre,r,0,-30),vCoat,z10,tGun2;
	ENDPROC
ENDMODULE
