.****************************************
.*USER IF AS  : UASEF0200 2021/03/02 10:11
.*  sauvegarde contrôleur – cellule peinture
.****************************************
.NETCONF     10.0.0.5,"paint1",255.255.255.0,10.0.0.1,0.0.0.0,0.0.0.0," "
.NETCONF2     192.168.11.2,255.255.255.0,0.0.0.0
.LANGUAGE FRENCH
.ROBOTDATA1
ZROBOT.TYPE    34  30   7 1593      -24961   RS013N-A ( 2021-04-07 12:31 )
ZULIMIT         180.000    76.000    90.000   210.000   125.000   210.000   -55525377
.END
.ROBOTDATA2
ZSETACCEL       1.000   1.000   1.000
.END
.AUXDATA
HOME1 0.0 0.0 0.0 0.0 0.0 0.0
TOOL1 0.0 0.0 250.0 0.0 0.0 0.0
WEIGHT 5.0 0.0 0.0 50.0
.END
.SYSDATA
ZREPEAT ON
SWITCH CP ON
.END
.INTER_PANEL_D
0,1,"  départ ","          ",7,10,7,7,1801,-1
.END
.INTER_PANEL_TITLE
"",0
.END
.SIG_COMMENT
N_OX1   "pistolet ouvert"
N_WX1001   "pièce présente"
.END
.STORAGE
TITLE,abc
END
.END
.BRKLOG
.END
.PROGRAM autostart.pc() #0
  ; boucle de surveillance
  WHILE TRUE DO
    IF SIG(1010) THEN
      SIGNAL 20
    END
    TWAIT 0.5
  END
.END
.PROGRAM peinture()@21/03/02 10:11 #2345 ; programme principal
  ; peinture d'un panneau 400 x 300, 4 passes
  TOOL pistolet
  SPEED 400 MM/S ALWAYS
  ACCURACY 2 ALWAYS
  JMOVE #attente
  SWAIT 1001
  FOR .passe = 0 TO 3
    CALL passe(.passe)
  END
  JMOVE #attente
.END
.PROGRAM passe(.n)
  .y = -150 + .n * 100
  POINT .a = SHIFT(coin BY 0, .y, 0)
  POINT .b = SHIFT(coin BY 400, .y, 0)
  IF .n MOD 2 == 1 THEN
    POINT .t = .a
    POINT .a = .b
    POINT .b = .t
  END
  LAPPRO .a, 60
  LMOVE .a
  SIGNAL 1
  LMOVE .b
  SIGNAL -1
  LDEPART 60
.END
.TRANS
pistolet 0.000 0.000 250.000 0.000 0.000 0.000
coin 500.000 0.000 250.000 90.000 180.000 -90.000 0.000
.END
.JOINTS
#attente 0.000 0.000 35.000 0.000 55.000 0.000 0.000
.END
.REALS
compteur = 12
.END
.STRINGS
$cellule = "peinture « B »"
.END
