#!/bin/sh
# Regenerates the binary fixtures of the disasm suite from the sources beside them.
# usage (from tests/golden/disasm): sh inputs/regen.sh PATH/TO/tmclasm
set -eu
T=$1
"$T" -o inputs/forms.bin inputs/forms.tmc
"$T" -f symbols -o inputs/forms.sym inputs/forms.tmc
"$T" -f datagrams --address 3 -o inputs/forms.dgm inputs/forms.tmc
"$T" --no-append-stop -o inputs/nostop.bin inputs/nostop.tmc
"$T" -c -o inputs/prog.o inputs/prog.tmc
: > inputs/empty.bin
# A record with a wrong checksum byte (the 3rd record's), and a size that is not a multiple of 8.
cp inputs/forms.bin inputs/badsum.bin
printf '\000' | dd of=inputs/badsum.bin bs=1 seek=23 conv=notrunc 2>/dev/null
head -c 21 inputs/forms.bin > inputs/odd.bin
cp ../link/inputs/libmotion.a inputs/lib.a
