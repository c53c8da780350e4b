MODULE CoatLib
  !# RobotWare 6 -- library module, functions return targets
  LOCAL CONST num GRID := 30;
  PERS tooldata tSpray := [TRUE,[[0,0,245],[1,0,0,0]],[1.2,[0,0,60],[1,0,0,0],0,0,0]];
  PERS wobjdata wTable := [FALSE,TRUE,"",[[650,0,200],[1,0,0,0]],[[0,0,0],[0.9961947,0,0,0.0871557]]];
  CONST robtarget pOrigin := [[0,0,100],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  VAR robtarget pNow;
  VAR bool bGunOn := FALSE;

  FUNC robtarget GridPoint(num col, num row)
    RETURN Offs(pOrigin, col * GRID, row * GRID, 0);
  ENDFUNC

  LOCAL PROC Gun(\switch On | switch Off)
    IF Present(On) THEN
      SetDO doSpray, 1;
      bGunOn := TRUE;
    ELSE
      SetDO doSpray, 0;
      bGunOn := FALSE;
    ENDIF
  ENDPROC

  PROC main()
    VAR num row := 0;
    MoveJ Offs(GridPoint(0, 0), 0, 0, 40), v1000, z50, tSpray \WObj:=wTable;
    MoveL GridPoint(0, 0), v400, fine, tSpray \WObj:=wTable;
    Gun \On;
    FOR row FROM 0 TO 2 STEP 2 DO
      MoveL GridPoint(4, row), v300, z1, tSpray \WObj:=wTable;
      MoveC GridPoint(5, row + 1), GridPoint(4, row + 2), v300, z1, tSpray \WObj:=wTable;
      MoveL GridPoint(0, row + 2), v300, z1, tSpray \WObj:=wTable;
      IF row < 2 THEN
        MoveC GridPoint(-1, row + 3), GridPoint(0, row + 4), v300, z1, tSpray \WObj:=wTable;
      ENDIF
    ENDFOR
    Gun \Off;
    pNow := CRobT(\Tool:=tSpray \WObj:=wTable);
    MoveL Offs(pNow, 0, 0, 60), v500, fine, tSpray \WObj:=wTable;
  ENDPROC
ENDMODULE
