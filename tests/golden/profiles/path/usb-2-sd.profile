# A user's own usb-2-sd, found first on TMCL_PROFILE_PATH: it hides the bundled one, which it is
# based on (a based-on line never means the file itself).
tmcl-profile 1
name usb-2-sd
title "USB-2-SD with a larger memory (ours)"
based-on usb-2-sd
program-memory 2048 ram
