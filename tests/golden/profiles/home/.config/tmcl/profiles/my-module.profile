# A module of our own: one axis, a small program memory, a few parameters.
tmcl-profile 1
name my-module
title "My module (firmware 2.01)"
source M "My module's manual, firmware 2.01"
firmware 4242V201 src=M:1
motors 1 src=M:1
program-memory 8 eeprom src=M:2
user-variables 16 eeprom=4 src=M:3
coordinates 0
commands 1-6 9-12 14-15 19-28 128-137 255 src=M:4
motion linear
axis 0 "Target position" -2147483648..2147483647 RW unit=μsteps src=M:5
axis 1 "Actual position" -2147483648..2147483647 RW unit=μsteps src=M:5
axis 4 "Maximum speed" 0..2047 RW default=100 src=M:5 unverified=default
axis 5 "Maximum acceleration" 0..2047 RW default=100 src=M:5 unverified=default
global 0 77 "Auto start mode" 0..1 RWA src=M:6
