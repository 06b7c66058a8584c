# generic: the profile used when no module is named. It accepts every opcode of opcodes.def and
# every parameter number without range or access checks, so any TMCL program assembles and runs.
# It drives six motors with the same motion core as the USB-2-SD and borrows that module's
# parameter tables and interrupt vectors, for parameter names and power-on defaults (a parameter
# number outside them starts at 0). See docs/profiles.md.
tmcl-profile 1
name generic
title "generic (any TMCL module)"
based-on usb-2-sd
firmware 0000V100  # module number 0: not a real module
motors 6  # Motor0..Motor5 of TMCLParam.tmc
program-memory unlimited
user-variables 256 eeprom=56
coordinates 21
parameters any
commands all
