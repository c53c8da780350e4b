%%%
  VERSION:1
  LANGUAGE:ENGLISH
%%%

MODULE Module1
    !***********************************************************
    !
    ! Module:  Module1
    !
    ! Description:
    !   Coating of the side panel, station 2
    !
    ! Author: cell integrator
    !
    ! Version: 1.0
    !
    !***********************************************************
    PERS tooldata tSprayGun:=[TRUE,[[0,0,235.5],[1,0,0,0]],[2.8,[0,0,90],[1,0,0,0],0,0,0]];
    TASK PERS wobjdata wobjPanel:=[FALSE,TRUE,"",[[640,-120,180],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];
    CONST robtarget Target_10:=[[20,40,120],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    CONST robtarget Target_20:=[[20,40,100],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    CONST robtarget Target_30:=[[180,40,100],[0,0,1,0],[0,-1,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    CONST robtarget Target_40:=[[208.2842712,80,100],[0,0,1,0],[0,-1,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    CONST robtarget Target_50:=[[180,120,100],[0,0,1,0],[0,-1,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    CONST robtarget Target_60:=[[20,120,100],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    CONST robtarget Target_70:=[[20,120,120],[0,0,1,0],[0,0,0,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
    !***********************************************************
    !
    ! Procedure main
    !
    !   This is the entry point of your program
    !
    !***********************************************************
    PROC main()
        ConfL\Off;
        ConfJ\Off;
        AccSet 70, 70;
        VelSet 100, 1000;
        FOR i FROM 1 TO 2 DO
            Path_10;
            TPWrite "Coat " \Num:=i;
        ENDFOR
        WaitTime 0.2;
    ENDPROC
    PROC Path_10()
        MoveJ Target_10,v1000,z100,tSprayGun\WObj:=wobjPanel;
        MoveL Target_20,v200,fine,tSprayGun\WObj:=wobjPanel;
        SetDO doGun1,1;
        MoveL Target_30,v300,z5,tSprayGun\WObj:=wobjPanel;
        MoveC Target_40,Target_50,v300,z5,tSprayGun\WObj:=wobjPanel;
        MoveL Target_60,v300,z1,tSprayGun\WObj:=wobjPanel;
        SetDO doGun1,0;
        MoveL Target_70,v500,fine,tSprayGun\WObj:=wobjPanel;
    ENDPROC
ENDMODULE
