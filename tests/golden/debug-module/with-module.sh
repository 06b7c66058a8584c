#!/bin/sh
# Runs tmclctl against a virtual module for the golden cases of `tmclctl PORT debug`:
#   with-module.sh TMCLRUN TMCLCTL tcp|pty [SERVER ARGS...] -- [TMCLCTL ARGS...] [-- TMCLCTL ARGS...]...
# starts `tmclrun --serve` (a TCP port the system picks, or a pseudo-terminal) with the server's
# arguments, then runs each tmclctl command in turn with PORT replaced by the server's port; the
# last one reads this script's standard input, another one a file named with a word "<FILE"
# among its arguments (else nothing). After each: "[tmclctl exit N]". The server's own
# notes (clients connecting) are dropped: they are the server's, pinned elsewhere.
run=$1; ctl=$2; transport=$3; shift 3
dir=$(mktemp -d "${TMPDIR:-/tmp}/tmcl-module-XXXXXX")
server=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do server="$server $1"; shift; done
case $transport in
  tcp) spec=tcp:127.0.0.1:0 ;;
  *) spec=pty ;;
esac
# shellcheck disable=SC2086
"$run" --serve $spec $server > "$dir/server.out" 2> "$dir/server.err" < /dev/null &
pid=$!
n=0
while ! [ -s "$dir/server.out" ] && [ $n -lt 200 ]; do sleep 0.05; n=$((n + 1)); done
first=$(head -n 1 "$dir/server.out")
case $transport in
  tcp) port=tcp:${first#listening on } ;;
  *) port=$first ;;
esac
# The tmclctl commands, split at "--".
cmds=""
while [ $# -gt 0 ]; do
  shift  # the "--"
  args=""
  input=/dev/null
  while [ $# -gt 0 ] && [ "$1" != "--" ]; do
    case $1 in
      PORT) args="$args $port" ;;
      "<"*) input=${1#<} ;;
      *) args="$args $1" ;;
    esac
    shift
  done
  if [ $# -gt 0 ] || [ "$input" != /dev/null ]; then
    # shellcheck disable=SC2086
    "$ctl" --timeout 5s $args < "$input"
  else
    # shellcheck disable=SC2086
    "$ctl" --timeout 5s $args
  fi
  echo "[tmclctl exit $?]"
done
kill "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
rm -rf "$dir"
