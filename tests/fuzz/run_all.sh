#!/usr/bin/env bash
# Builds every libFuzzer target with clang and runs each for N seconds (default 60) on a corpus
# seeded from the examples and golden tests. Crashes land in tests/fuzz/findings/<target>/.
# usage: tests/fuzz/run_all.sh [SECONDS] [TARGET...]
#        tests/fuzz/run_all.sh --seed TARGET FOLDER   (only copies TARGET's seeds into FOLDER; tested by
#        tests/profiles/fuzz_seeds.sh)
set -euo pipefail
cd "$(dirname "$0")/../.."

# Seeds: sources for the source fuzzers, profiles for the profile reader, images for the image fuzzers.
seed() {
  local t=$1 corpus=$2
  case "$t" in
    fuzz_asm) find examples tests/golden include_files -name '*.tmc' -o -name '*.inc' | head -500 | xargs -r cp -t "$corpus" 2>/dev/null || true ;;
    fuzz_profile) find vm/isa/profiles tests/golden/profiles -name '*.profile' | xargs -r cp -t "$corpus" 2>/dev/null || true ;;
    fuzz_symbols) find tests/golden -name '*.sym' -o -name '*.golden' | head -200 | xargs -r cp -t "$corpus" 2>/dev/null || true ;;
    *) find tests/golden examples -name '*.bin' | head -200 | xargs -r cp -t "$corpus" 2>/dev/null || true ;;
  esac
  if [ -d "tests/fuzz/seeds/$t" ]; then cp -r "tests/fuzz/seeds/$t/." "$corpus/"; fi
}
if [ "${1:-}" = --seed ]; then
  seed "$2" "$3"
  exit 0
fi

seconds=${1:-60}
shift || true
build=build-fuzz
CC=clang CXX=clang++ cmake -S . -B "$build" -DTMCL_FUZZ=ON -DBUILD_TESTING=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for f in tests/fuzz/fuzz_*.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi
cmake --build "$build" -j2 --target "${targets[@]}" >/dev/null
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  mkdir -p "$corpus" "tests/fuzz/findings/$t"
  seed "$t" "$corpus"
  echo "== $t: ${seconds}s"
  "$build/tests/fuzz/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="tests/fuzz/findings/$t/" "$corpus" 2>&1 | grep -E '^(#[0-9]+ *(DONE|pulse)|==|SUMMARY|Done)' | tail -3
done
