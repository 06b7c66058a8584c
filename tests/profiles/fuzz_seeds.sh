#!/usr/bin/env bash
# tests/fuzz/run_all.sh seeds fuzz_profile, the profile reader's fuzzer, with every profile file of the
# repository: the bundled ones (vm/isa/profiles/) and the golden cases' (tests/golden/profiles/,
# good and bad). Runs only the seeding (--seed), which needs neither clang nor a build.
# usage: fuzz_seeds.sh SOURCE_DIR
set -u
src=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bash "$src/tests/fuzz/run_all.sh" --seed fuzz_profile "$work" || { echo "tests/fuzz/run_all.sh --seed failed"; exit 1; }
fail=0
for f in "$src"/vm/isa/profiles/*.profile "$src"/tests/golden/profiles/*.profile; do
  [ -e "$f" ] || { echo "no profile files in $(dirname "$f")"; fail=1; continue; }
  if [ ! -f "$work/$(basename "$f")" ]; then
    echo "not seeded: ${f#"$src"/}"
    fail=1
  fi
done
n=$(find "$work" -name '*.profile' | wc -l)
[ "$n" -ge 13 ] || { echo "only $n profile seeds"; fail=1; }
[ $fail -eq 0 ] && echo "fuzz_profile seeded with $n profile files"
exit $fail
