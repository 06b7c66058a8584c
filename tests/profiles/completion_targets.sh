#!/usr/bin/env bash
# -t completes every target found (tmclasm --list-targets): the bundled ones, aliases and a
# user's profile on TMCL_PROFILE_PATH, for tmclasm, tmclrun and tmclctl through the one bash
# completion (cli/completion/tmcl, which asks each tool: TOOL --complete); a value with a '/'
# completes profile files. Needs bash alone.
# usage: completion_targets.sh TOOLS_DIR SOURCE_DIR
set -u
tools=$1 src=$2
export PATH="$tools:$PATH"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/path" "$work/dir"
printf 'tmcl-profile 1\nname my-own\nbased-on generic\n' > "$work/path/my-own.profile"
: > "$work/dir/a.profile"
: > "$work/dir/b.txt"
export TMCL_PROFILE_PATH="$work/path" HOME="$work"
fail=0
# shellcheck source=/dev/null
source "$src/cli/completion/tmcl" || { echo "sourcing cli/completion/tmcl failed"; exit 1; }

complete_line() {  # LINE : COMPREPLY for its last word, a line each
  COMP_LINE=$1 COMP_POINT=${#1}
  COMPREPLY=()
  _tmcl_complete "${1%% *}"
  printf '%s\n' "${COMPREPLY[@]}"
}

expect() {  # DESCRIPTION WANT GOT
  if ! grep -qx -- "$2" <<< "$3"; then
    echo "FAIL: $1: '$2' not in:"
    echo "$3"
    fail=1
  fi
}

for tool in tmclasm tmclrun tmclctl; do
  got=$(complete_line "$tool -t tm")
  expect "$tool -t tm" tmcm-1110 "$got"
  expect "$tool -t tm" tmcm-351 "$got"
  got=$(complete_line "$tool --target p")
  expect "$tool --target p" pd60-1260 "$got"
  got=$(complete_line "$tool -t my")
  expect "$tool -t my (TMCL_PROFILE_PATH)" my-own "$got"
  got=$(complete_line "$tool -t $work/dir/")
  expect "$tool -t DIR/" "$work/dir/a.profile" "$got"
  if grep -q b.txt <<< "$got"; then echo "FAIL: $tool -t DIR/ offers b.txt"; fail=1; fi
done
got=$(complete_line "tmclasm --show-target us")
expect "tmclasm --show-target us" usb-2-sd "$got"
exit $fail
