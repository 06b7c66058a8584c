#!/usr/bin/env bash
# -t completes every target found (tmclasm --list-targets): the bundled ones, aliases and a
# user's profile on TMCL_PROFILE_PATH, in the bash completions of tmclasm, tmclrun and tmclctl;
# a value with a '/' completes profile files. bash-completion's helpers are stubbed (only what
# the completions call), so the test needs bash alone.
# usage: completion_targets.sh TOOLS_DIR SOURCE_DIR
set -u
tools=$1 src=$2
export PATH="$tools:$PATH"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/path" "$work/dir"
printf 'tmcl-profile 1\nname my-own\nbased-on generic\n' > "$work/path/my-own.profile"
: > "$work/dir/a.profile"
export TMCL_PROFILE_PATH="$work/path" HOME="$work"
fail=0

_init_completion() {
  words=("${COMP_WORDS[@]}")
  cword=$COMP_CWORD
  cur=${COMP_WORDS[COMP_CWORD]}
  prev=${COMP_WORDS[COMP_CWORD-1]}
}
_filedir() { COMPREPLY+=("$cur-file"); }  # stands for bash-completion's file completion
compopt() { :; }

complete_words() {  # TOOL WORD... : COMPREPLY for the last word
  local tool=$1
  shift
  COMP_WORDS=("$tool" "$@")
  COMP_CWORD=$(( ${#COMP_WORDS[@]} - 1 ))
  COMPREPLY=()
  "_${tool//-/_}"
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
  # shellcheck disable=SC1090
  source "$src/cli/completion/$tool"
  got=$(complete_words "$tool" -t tm)
  expect "$tool -t tm" tmcm-1110 "$got"
  expect "$tool -t tm" tmcm-351 "$got"
  got=$(complete_words "$tool" --target p)
  expect "$tool --target p" pd60-1260 "$got"
  got=$(complete_words "$tool" -t my)
  expect "$tool -t my (TMCL_PROFILE_PATH)" my-own "$got"
  got=$(complete_words "$tool" -t "$work/dir/")
  expect "$tool -t DIR/" "$work/dir/-file" "$got"
done
got=$(complete_words tmclasm --show-target us)
expect "tmclasm --show-target us" usb-2-sd "$got"
exit $fail
