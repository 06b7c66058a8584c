# The zap at frob-b's number, the glim rate at another (see frob-a.profile).
tmcl-profile 1
name frob-c
firmware 0042V100
motors 1
program-memory 64 ram
commands all
motion linear
axis 0 "Target position" -2147483648..2147483647 RW
axis 131 "Frob glim rate" -2147483648..2147483647 R
axis 149 "Frob zap flag" 0..1 RW
