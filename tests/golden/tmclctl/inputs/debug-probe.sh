#!/bin/sh
# `tmclctl PORT debug --probe` against a served module, for the debug-probe*.run golden cases:
#   debug-probe.sh TMCLRUN TMCLCTL DIR [TMCLCTL-OPTIONS...] -- [TMCLRUN-OPTIONS...]
# Serves a USB-2-SD on a pseudo-terminal with inputs/probe-module.tmc preloaded (and the
# tmclrun options: --variant, --faults), reads its program (upload) before and after the probe
# and says whether it is the same. The pseudo-terminal's path is shown as PTY (it differs per run).
run=$1 ctl=$2 dir=$3
shift 3
opts=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do opts="$opts $1"; shift; done
[ $# -gt 0 ] && shift
rm -f "$dir/pty" "$dir/before.bin" "$dir/after.bin"  # a case's commands share DIR
"$run" -t usb-2-sd --serve pty --max-wall-time 120s "$@" "$(dirname "$0")/probe-module.tmc" > "$dir/pty" 2> "$dir/server.err" &
server=$!
n=0
while [ ! -s "$dir/pty" ] && [ $n -lt 600 ]; do sleep 0.05; n=$((n + 1)); done
pty=$(head -n 1 "$dir/pty")
"$ctl" --timeout 5s -q "$pty" upload -o "$dir/before.bin" > /dev/null 2>&1
# shellcheck disable=SC2086  # the options are words
(cd "$dir" && "$ctl" $opts "$pty" debug --probe > out 2> err)  # a program not put back is saved here
status=$?
sed "s#$pty#PTY#g" "$dir/out"
sed "s#$pty#PTY#g" "$dir/err" >&2
if "$ctl" --timeout 5s -q "$pty" upload -o "$dir/after.bin" > /dev/null 2>"$dir/after.err" && [ -s "$dir/before.bin" ]; then
  if cmp -s "$dir/before.bin" "$dir/after.bin"; then echo "== the module's program afterwards: as before"; else echo "== the module's program afterwards: CHANGED"; fi
else
  echo "== the module's program could not be read before or after"
fi
kill "$server" 2> /dev/null
wait "$server" 2> /dev/null
exit $status
