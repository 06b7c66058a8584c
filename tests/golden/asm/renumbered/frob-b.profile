# The TMC429 modules' numbering of frob-a's zap (see frob-a.profile).
tmcl-profile 1
name frob-b
firmware 0042V100
motors 1
program-memory 64 ram
commands all
motion linear
axis 0 "Target position" -2147483648..2147483647 RW
axis 149 "Frob zap flag" 0..1 RW
