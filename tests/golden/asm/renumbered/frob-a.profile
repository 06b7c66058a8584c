# A test module for target-renumbered-hint.tmc: its names are no bundled module's, so the notes
# name only the modules of this folder and a new bundled profile changes nothing there.
tmcl-profile 1
name frob-a
firmware 0042V100
motors 1
program-memory 64 ram
commands all
motion linear
axis 0 "Target position" -2147483648..2147483647 RW
axis 26 "Frob zap enable" 0..1 RW
axis 29 "Frob glim rate" -2147483648..2147483647 R
