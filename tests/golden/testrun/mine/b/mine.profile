tmcl-profile 1
name mine
title "mine, a TMCM-1110"
based-on tmcm-1110
