#!/bin/sh
# The headless Neovim test of tmcl-lsp (nvim_test.lua). Skipped (exit 77) when nvim is absent;
# .ci/run installs it with: apt-get install -y neovim
# usage: nvim_test.sh TMCL_LSP_BINARY TEST_DIR
if ! command -v nvim >/dev/null 2>&1; then
  echo "SKIP: nvim is not installed (apt-get install -y neovim)"
  exit 77
fi
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
printf 'Speed = 1000\nLoop:\nsap 4,0,Speed\n  MVP ABS, 0, 100\n  JA Lop\n' > "$dir/prog.tmc"
# A test file (*.tmctest), found by cli/lsp/editors/vim/ftdetect: its diagnostics come from the same server.
printf 'Top:\n  STOP\n' > "$dir/good.tmc"
printf '# a test\nprogram good.tmc\nexpect at end pc = Tpo\n' > "$dir/check.tmctest"
HOME="$dir" XDG_CACHE_HOME="$dir" XDG_STATE_HOME="$dir" TMCL_LSP="$1" TMC_FILE="$dir/prog.tmc" \
  TMCTEST_FILE="$dir/check.tmctest" TMCL_FTDETECT="$2/../../cli/lsp/editors/vim/ftdetect/tmcl.vim" \
  timeout 60 nvim --headless --clean -u NONE -c "luafile $2/nvim_test.lua"
