#!/usr/bin/env bash
# Every scene under scenes/ loads and renders: tiny film, 1 spp, exit status 0 and an EXR written.
# Each scene declares the res_x, res_y and spp defaults this relies on (scenes/*/README.md).
# A scene whose build-time mesh is missing (bunny_sphere, the caustic gallery's meshes without
# node/npm) is skipped, loudly.
# Usage: test_scenes.sh SNELL SCENES_DIR
set -u
SNELL=$1
SCENES=$2
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
pass=0; fail=0; skip=0
# build_time_file_missing SCENE: prints and succeeds when SCENE names a file that the build makes
# (its folder's .gitignore lists it, or the folder it lies in) and that file is absent.
build_time_file_missing() {
  local dir f ignore
  dir=$(dirname "$1")
  ignore="$dir/.gitignore"
  [ -f "$ignore" ] || return 1
  for f in $(sed -n 's/.*name="filename" value="\([^"]*\)".*/\1/p' "$1"); do
    [ -e "$dir/$f" ] && continue
    if grep -qxF "$f" "$ignore" || grep -qxF "${f%%/*}/" "$ignore"; then echo "$f"; return 0; fi
  done
  return 1
}
for scene in "$SCENES"/*/*.xml; do
  name=$(basename "$scene" .xml)
  if missing=$(build_time_file_missing "$scene"); then
    echo "SKIP $scene: $missing was not generated at build time (needs node and npm)"
    skip=$((skip + 1)); continue
  fi
  if "$SNELL" render "$scene" -D res_x=16 -D res_y=12 --spp 1 -t 2 -q -o "$TMP/$name.exr" >"$TMP/$name.log" 2>&1 &&
     [ -s "$TMP/$name.exr" ]; then
    echo "ok   $scene"; pass=$((pass + 1))
  else
    echo "FAIL $scene"; sed 's/^/     /' "$TMP/$name.log"; fail=$((fail + 1))
  fi
done
# An empty glob would pass vacuously.
[ $((pass + fail)) -gt 0 ] || { echo "FAIL no scenes found under $SCENES"; fail=1; }
echo "$pass passed, $fail failed, $skip skipped"
[ "$fail" -eq 0 ]
