MODULE Stripes(SYSMODULE)
  ! hand written -- stripes across the plate, 25 mm pitch
  ! rev B: speed raised to 250 mm/s, zone z3
  PERS tooldata tool_gun := [TRUE, [[0, 0, 250], [1, 0, 0, 0]], [1.5, [0, 0, 80], [1, 0, 0, 0], 0, 0, 0]];
  PERS wobjdata wo_plate := [FALSE, TRUE, "", [[600, -60, 200], [1, 0, 0, 0]], [[0, 0, 0], [1, 0, 0, 0]]];
  CONST robtarget pCorner{2} := [
    [[0, 0, 100], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]],
    [[150, 0, 100], [0, 0, 1, 0], [-1, 0, -1, 0], [9E9, 9E9, 9E9, 9E9, 9E9, 9E9]]];
  CONST num nPitch := 25;
  PERS num nStripes := 4;
  PERS num nDone := 0;
  VAR robtarget pFrom;
  VAR robtarget pTo;

  PROC main()
    nDone := 0;
    TPErase;
    TPWrite "Stripes: " + NumToStr(nStripes, 0);
    MoveJ Offs(pCorner{1}, 0, 0, 50), v800, z20, tool_gun \WObj:=wo_plate;
    stripes nStripes, nDone;
    MoveJ Offs(pCorner{1}, 0, 0, 50), v800, fine, tool_gun \WObj:=wo_plate;
    TPWrite "done, stripes = " \Num:=nDone;
  ENDPROC

  PROC stripes(num count, PERS num done)
    VAR num k := 0;
    WHILE k < count DO
      pFrom := Offs(pCorner{1}, 0, k * nPitch, 0);
      pTo := Offs(pCorner{2}, 0, k * nPitch, 0);
      IF k MOD 2 = 1 THEN
        pFrom := Offs(pCorner{2}, 0, k * nPitch, 0);
        pTo := Offs(pCorner{1}, 0, k * nPitch, 0);
      ENDIF
      MoveL pFrom, v200 \V:=250, z5 \Z:=2, tool_gun \WObj:=wo_plate;
      SetDO do_spray, 1;
      MoveL pTo, v200 \V:=250, z5 \Z:=2, tool_gun \WObj:=wo_plate;
      SetDO do_spray, 0;
      Incr k;
      done := done + 1;
    ENDWHILE
    WaitTime \InPos, 0.5;
  ENDPROC
ENDMODULE
