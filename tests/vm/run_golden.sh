#!/bin/sh
# Golden tests for tmclrun. Each folder under GOLDEN_DIR is one case:
#   cmd       one shell command per line ('#' lines are comments); `tmclrun` is the binary under
#             test, @CASE@ the case folder relative to the repository root, @TMP@ a fresh
#             temporary folder shared by the case's commands (e.g. an EEPROM file across runs)
#   expected  every command, its standard output, its standard error and its exit status
# Commands run from the repository root, so file names in traces and messages are stable.
# usage: run_golden.sh TMCLRUN GOLDEN_DIR ROOT [--update]
#   --update rewrites every `expected` from the actual output, for review with git diff.
set -u
bin=$1
golden=$2
root=$3
update=${4:-}
fail=0
count=0
for dir in "$golden"/*/; do
  dir=${dir%/}
  name=$(basename "$dir")
  rel=${dir#"$root"/}
  tmp=$(mktemp -d)
  actual=$tmp/.actual
  : > "$actual"
  while IFS= read -r line || [ -n "$line" ]; do
    case $line in '' | '#'*) continue ;; esac
    cmd=$(printf '%s\n' "$line" | sed "s|@CASE@|$rel|g; s|@TMP@|$tmp|g")
    printf '$ %s\n' "$line" >> "$actual"
    (cd "$root" && TMCLRUN=$bin sh -c "tmclrun() { \"\$TMCLRUN\" \"\$@\"; }; $cmd") > "$tmp/.out" 2> "$tmp/.err"
    status=$?
    sed "s|$tmp|@TMP@|g" "$tmp/.out" >> "$actual"
    if [ -s "$tmp/.err" ]; then
      echo "-- stderr" >> "$actual"
      sed "s|$tmp|@TMP@|g" "$tmp/.err" >> "$actual"
    fi
    printf '[exit %d]\n' "$status" >> "$actual"
  done < "$dir/cmd"
  if [ "$update" = --update ]; then
    cp "$actual" "$dir/expected"
  elif ! diff -u "$dir/expected" "$actual" > "$tmp/.diff" 2>&1; then
    echo "FAIL: $name"
    cat "$tmp/.diff"
    fail=$((fail + 1))
  fi
  count=$((count + 1))
  rm -rf "$tmp"
done
echo "$count golden cases, $fail failed"
[ "$fail" -eq 0 ]
