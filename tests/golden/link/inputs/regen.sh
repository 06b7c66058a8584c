#!/bin/sh
# Regenerates the binary fixtures of the link suite from the sources beside them.
# usage (from tests/golden/link): sh inputs/regen.sh PATH/TO/tmclasm
# The objects record file names as given here (inputs/NAME.tmc), as the messages show them.
set -eu
T=$1
for f in homing main jog dup undefined checked param useparam nostop big; do
  "$T" -c -o inputs/$f.o inputs/$f.tmc
done
"$T" -c -t usb-2-sd -o inputs/usb.o inputs/usb.tmc
"$T" -c -t tmc2300-eval -o inputs/tmc2300.o inputs/tmc2300.tmc
"$T" -f lib -o inputs/libmotion.a inputs/jog.o inputs/homing.o
# Damaged objects: cut short, one byte flipped, a future version.
head -c 40 inputs/homing.o > inputs/truncated.o
cp inputs/homing.o inputs/badcrc.o
printf '\377' | dd of=inputs/badcrc.o bs=1 seek=30 conv=notrunc 2>/dev/null
cp inputs/homing.o inputs/version2.o
printf '\002' | dd of=inputs/version2.o bs=1 seek=8 conv=notrunc 2>/dev/null
