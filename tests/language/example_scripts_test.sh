#!/usr/bin/env bash
# An example script without a .expect (scripts/*.bsp: the goblet of the README's main job, the
# head profile, the tree comparison; one test each, tests/language/CMakeLists.txt) runs to
# completion on a copy of scripts/ and models/, and every mesh it exports reads back (import
# refuses open or non-manifold meshes) with a positive volume; every picture is a PNG, every plot
# a complete SVG.   example_scripts_test.sh SCULPT SOURCE_DIR NAME.bsp
set -u
sculpt=$1
source_dir=$2
name=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r "$source_dir/scripts" "$source_dir/models" "$work/"
failures=0
script="$work/scripts/$name"
output=$("$sculpt" "$script" 2>&1)
status=$?
if [ "$status" -ne 0 ]; then
  echo "FAIL $name: exit status $status"; echo "$output" | tail -n 5
  failures=$((failures + 1))
fi
meshes=0
for mesh in "$work"/out/*.off "$work"/out/*.obj "$work"/out/*.stl "$work"/out/*.ply; do
  [ -e "$mesh" ] || continue
  meshes=$((meshes + 1))
  volume=$("$sculpt" -e "print(volume(import(\"$mesh\")))" 2>&1)
  if ! awk -v v="$volume" 'BEGIN { exit !(v + 0 > 0) }'; then
    echo "FAIL $(basename "$mesh"): $volume"
    failures=$((failures + 1))
  fi
done
for svg in "$work"/out/*.svg; do
  [ -e "$svg" ] || continue
  grep -q "</svg>" "$svg" || { echo "FAIL $(basename "$svg"): not a complete SVG"; failures=$((failures + 1)); }
done
for png in "$work"/out/*.png; do
  [ -e "$png" ] || continue
  [ "$(head -c 8 "$png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] ||
    { echo "FAIL $(basename "$png"): not a PNG"; failures=$((failures + 1)); }
done
echo "$name: $meshes meshes read back, $failures failures"
[ "$failures" -eq 0 ]
