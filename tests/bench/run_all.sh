#!/usr/bin/env bash
# Runs every benchmark given on the command line and prints one table:
# figure | goal | measured | machine. Each benchmark prints "figure<TAB>goal<TAB>measured" rows.
set -u
machine="$(grep -m1 'model name' /proc/cpuinfo 2>/dev/null | sed 's/.*: //; s/  */ /g'), $(nproc) cores"
printf '| figure | goal | measured | machine |\n|---|---|---|---|\n'
status=0
for b in "$@"; do
  if ! out=$("$b"); then
    echo "benchmark $b failed" >&2
    status=1
  fi
  while IFS=$'\t' read -r figure goal measured; do
    [ -n "$figure" ] && printf '| %s | %s | %s | %s |\n' "$figure" "$goal" "$measured" "$machine"
  done <<< "$out"
done
exit $status
