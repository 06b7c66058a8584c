tmcl-profile 1
name bad module
title "A profile with mistakes"
firmware 42V1
moters 2
program-memory 100 flash
commands 1-6 SOI
axis 4 "Maximum speed" 2047..0 RW
axis 5 "Maximum acceleration" 0..2047 RWX defualt=5
global 2 3 "user variable" 0..1 RW
