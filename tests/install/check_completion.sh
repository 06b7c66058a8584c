#!/usr/bin/env bash
# The bash completion (cli/completion/tmcl) in a bash without the bash-completion package: every
# tool completes its options, their values (targets, formats, warning names after -Wno-, motion
# cores, --serve transports), the files each option and operand takes, and tmclctl's PORT,
# COMMAND and parameter kinds; all from the tools' own tables (TOOL --complete).
# Run as: bash check_completion.sh <folder of the built tools> <source dir>
set -u
tools=$1 root=$2
export PATH="$tools:$PATH"
work=$(mktemp -d "${TMPDIR:-/tmp}/tmcl-completion.XXXXXX")
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# Only the bundled profiles: none of the user's (~/.config/tmcl/profiles, TMCL_PROFILE_PATH).
export HOME="$work" XDG_CONFIG_HOME="$work/config"
unset TMCL_PROFILE_PATH
mkdir sub && touch prog.tmc lib.inc prog.bin prog.dgm motion.svg notes.txt sub/x.tmc homing.tmctest

failures=0
if declare -F _init_completion >/dev/null; then
  echo "bash-completion is loaded: this test wants a bash without it"; exit 1
fi
# shellcheck source=/dev/null
source "$root/cli/completion/tmcl" || { echo "sourcing cli/completion/tmcl failed"; exit 1; }
for tool in tmclasm tmclrun tmclctl tmcl-lsp; do
  [[ $(complete -p "$tool" 2>/dev/null) == *"-F _tmcl_complete"* ]] || { echo "no completion for $tool"; failures=$((failures + 1)); }
done

# expect LINE WANT...: completing at the end of LINE offers exactly WANT (in any order).
expect() {
  local line=$1
  shift
  COMP_LINE=$line COMP_POINT=${#line}
  _tmcl_complete "${line%% *}" 2>"$work/err"
  local got want
  got=$(printf '%s\n' "${COMPREPLY[@]}" | sort | tr '\n' ' ')
  want=$(printf '%s\n' "$@" | sort | tr '\n' ' ')
  if [[ "$got" != "$want" || -s "$work/err" ]]; then
    echo "completing '$line': expected [$want], got [$got] $(cat "$work/err")"
    failures=$((failures + 1))
  fi
}

# The bundled targets, by name and alias, read from the profile folder: no list is kept here, so
# a new profile file changes nothing in this test.
targets=()
for f in "$root"/vm/isa/profiles/*.profile; do
  targets+=("$(basename "$f" .profile)")
  read -ra aliases <<< "$(sed -n 's/^alias[[:space:]]\{1,\}//p' "$f" | sed 's/#.*//')"
  targets+=("${aliases[@]}")
done
# starting PREFIX: the targets that start with PREFIX.
starting() { local t; for t in "${targets[@]}"; do [[ $t == "$1"* ]] && echo "$t"; done; }
((${#targets[@]} >= 11)) || { echo "no profiles found in $root/vm/isa/profiles"; failures=$((failures + 1)); }

expect "tmclasm --tar" --target
expect "tmclasm --target=us" $(starting us)
expect "tmclasm -t tmc" $(starting tmc)
expect "tmclasm -t " $(starting "")
expect "tmclasm --format l" listing lib
expect "tmclasm -Wno-unr" -Wno-unreachable
expect "tmclasm -Werror=eeprom" eeprom-wear  # bash replaces what follows the "="
expect "tmclasm --no-a" --no-analysis --no-append-stop
expect "tmclasm " sub prog.tmc lib.inc
expect "tmclasm -d " sub prog.bin prog.dgm
expect "tmclasm -I " sub
expect "tmclrun --plot " sub motion.svg
expect "tmclrun --plot=mo" motion.svg
expect "tmclrun --motion tmc" tmc429 tmc4361 tmc5160 tmc5240
expect "tmclrun --serve tcp:" 127.0.0.1:2001
expect "tmclrun -Wno-reti" -Wno-reti
expect "tmclrun --debug-c" --debug-commands
expect "tmclrun " sub prog.tmc prog.bin prog.dgm
expect "tmclrun --test " sub homing.tmctest
expect "tmclrun --test -j 2 homing.tmctest " sub homing.tmctest
expect "tmclctl /dev/null st" status step stop store
expect "tmclctl tcp:127.0.0.1:2001 get " ap gp io
expect "tmclctl --baud 1152" 115200
expect "tmclctl tcp:127.0.0.1:2001 download " sub prog.tmc prog.bin prog.dgm
expect "tmclctl tcp:127.0.0.1:2001 test " sub homing.tmctest
expect "tmcl-lsp --s" --stdio
# Hidden options are not offered.
expect "tmclasm --list-o"

if ((failures > 0)); then
  echo "completion: $failures problem(s)"
  exit 1
fi
echo "completion: every tool completes itself in a bash without bash-completion"
