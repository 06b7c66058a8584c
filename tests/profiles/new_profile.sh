#!/usr/bin/env bash
# A new module profile is one file (and its source table, tests/data/modules/NAME-*.tsv): every
# list of targets follows the profile folder, none is kept by hand (docs/architecture.md, "A new
# module profile"; issue 35). Checked two ways:
# - every file of vm/isa/profiles/ is a bundled target of --list-targets, of -t's completion in
#   every tool, of `-t NAME` and of the table in docs/profiles.md, and has a source table;
# - no golden file or document (but docs/profiles.md) lists the bundled modules, so that a new
#   profile changes none (issue 42);
# - a copy of a profile under a new name in a profile folder of its own (as a bundled one is
#   compiled in from vm/isa/profiles/ by vm/isa/embed_files.cmake, which this runs on the copy) is
#   at once a target everywhere, and no message of an unknown target changes.
# usage: new_profile.sh TOOLS_DIR SOURCE_DIR [CMAKE]
set -u
tools=$1 src=$2 cmake=${3:-cmake}
export PATH="$tools:$PATH"
work=$(mktemp -d "${TMPDIR:-/tmp}/tmcl-new-profile.XXXXXX")
trap 'rm -rf "$work"' EXIT
export HOME="$work" XDG_CONFIG_HOME="$work/config"
unset TMCL_PROFILE_PATH
cd "$work" || exit 1
printf '  STOP\n' > prog.tmc
fail=0
problem() { echo "FAIL: $*"; fail=1; }

# shellcheck source=/dev/null
source "$src/cli/completion/tmcl" || { echo "sourcing cli/completion/tmcl failed"; exit 1; }
completions() {  # LINE: what completing its last word offers, a line each
  COMP_LINE=$1 COMP_POINT=${#1}
  COMPREPLY=()
  _tmcl_complete "${1%% *}"
  printf '%s\n' "${COMPREPLY[@]}"
}

# is_target NAME ORIGIN: NAME is a target everywhere, listed as coming from ORIGIN.
is_target() {
  local name=$1 origin=$2 tool
  grep -Eq "^$name +.* +$origin\$" <<< "$(tmclasm --list-targets)" || problem "--list-targets: no '$name' from $origin"
  for tool in tmclasm tmclrun tmclctl; do
    grep -qx -- "$name" <<< "$(completions "$tool -t $name")" || problem "$tool -t $name: not completed"
  done
  tmclasm -t "$name" -o prog.bin prog.tmc || problem "tmclasm -t $name: refused"
  tmclasm --show-target "$name" | grep -qx "name $name" || problem "tmclasm --show-target $name"
}

# 1. The bundled profiles, as the folder has them.
count=0
for f in "$src"/vm/isa/profiles/*.profile; do
  name=$(basename "$f" .profile)
  count=$((count + 1))
  is_target "$name" bundled
  grep -q "^| \`$name\`" "$src/docs/profiles.md" || problem "docs/profiles.md: no row for $name in the table of bundled profiles"
  upper=$(tr '[:lower:]' '[:upper:]' <<< "$name")
  [[ $name == generic ]] || compgen -G "$src/tests/data/modules/$upper-*.tsv" >/dev/null ||
    problem "$name: no source table tests/data/modules/$upper-*.tsv"
done
((count >= 11)) || problem "only $count profiles in $src/vm/isa/profiles"

# 1b. No golden file or document lists the bundled modules by hand (a list that every new profile
# would change): no golden line, and no paragraph of docs/ but profiles.md's table, names more
# than half of them (case-insensitive, so TMCM-1260.inc counts as tmcm-1260).
names=()
for f in "$src"/vm/isa/profiles/*.profile; do names+=("$(basename "$f" .profile)"); done
half=$(( ${#names[@]} / 2 ))
pattern=$(IFS='|'; echo "${names[*]}")
too_many() {  # FILE RS: the records (lines, or paragraphs with RS="") naming more than half
  awk -v RS="$2" -v pat="$pattern" -v half="$half" -v file="$1" '
    { n = 0; split(pat, all, "|"); low = tolower($0)
      for (i in all) if (index(low, all[i])) n++
      if (n > half) print file ": " n " bundled modules named in one " (RS == "" ? "paragraph" : "line") ": " substr($0, 1, 100) }' "$1"
}
while IFS= read -r f; do
  out=$(too_many "$f" '\n'); [[ -z $out ]] || problem "$out"
done < <(find "$src/tests/golden" -name '*.golden')
while IFS= read -r f; do
  out=$(too_many "$f" ''); [[ -z $out ]] || problem "$out (say 'every bundled module' and point to --list-targets or docs/profiles.md)"
done < <(find "$src/docs" -name '*.md' ! -path '*/profiles.md' ! -path '*/conformance/*')

# 2. A new profile: tmcm-1110's facts under the name tmcm-9110 (its aliases are tmcm-1110's).
before=$(tmclasm -t usb2sd prog.tmc 2>&1)
mkdir folder
sed -e 's/^name tmcm-1110$/name tmcm-9110/' -e '/^alias /d' "$src/vm/isa/profiles/tmcm-1110.profile" > folder/tmcm-9110.profile
grep -qx "name tmcm-9110" folder/tmcm-9110.profile || problem "tmcm-1110.profile has no line 'name tmcm-1110'"
export TMCL_PROFILE_PATH="$work/folder"
is_target tmcm-9110 "$work/folder/tmcm-9110.profile"
after=$(tmclasm -t usb2sd prog.tmc 2>&1)
[[ $before == "$after" ]] || problem "a new profile changed the message of an unknown target:"$'\n'"$before"$'\n'"$after"
grep -q "tmcm-1110" <<< "$after" && problem "the message of an unknown target lists the targets: $after"
tmclrun -t tmcm-9110 prog.tmc > /dev/null || problem "tmclrun -t tmcm-9110: refused"
unset TMCL_PROFILE_PATH

# 3. The build bundles the folder: the embedding, run on the folder with the new file, holds it.
cp "$src"/vm/isa/profiles/*.profile folder/
cat > embed.cmake <<EOF
include("$src/vm/isa/embed_files.cmake")
file(GLOB files "$work/folder/*.profile")
tmcl_embed_files("$work/bundled.cpp" bundled_profile_files \${files})
EOF
"$cmake" -P embed.cmake || problem "embed_files.cmake failed"
for f in folder/*.profile; do
  grep -q "{\"$(basename "$f")\"" bundled.cpp || problem "the embedded profiles lack $(basename "$f")"
done
grep -q 'file(GLOB TMCL_PROFILE_FILES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/profiles/\*.profile)' "$src/vm/isa/CMakeLists.txt" ||
  problem "vm/isa/CMakeLists.txt no longer bundles every file of profiles/"

((fail == 0)) && echo "new_profile: a profile file is a target everywhere, with nothing registered by hand"
exit $fail
