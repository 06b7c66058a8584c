tmcl-profile 1
name mine
title "mine, a USB-2-SD"
based-on usb-2-sd
