#!/bin/sh
# The main job on the default scene. Today (foundation): load and check the default scene, build
# its surface texture and summarise it, generate the texture gallery and shaded previews.
# hapticd takes over here when the servo exists (issue 3).
# Usage: ./demo.sh [BUILD_DIR]   (make demo builds first, then calls this)
set -eu
BUILD=${1:-build}
OUT=out/demo
mkdir -p "$OUT"
TT="$BUILD/textures/texturetool"
SI="$BUILD/scenes/scene-info"

echo "== default scene: scenes/default.yaml"
"$SI" scenes/default.yaml --texture-out "$OUT/default_surface.png"
"$TT" preview "$OUT/default_surface.png" "$OUT/default_surface_preview.png"

echo
echo "== texture gallery (512^2, seed 1) -> $OUT/"
n=0
for kind in bricks vvalley grooves pebbles wood sine dimples tilted; do
  n=$((n + 1))
  printf '[%d/8] %-8s ' "$n" "$kind"
  "$TT" generate "$kind" --size 512 --out "$OUT/$kind.png" | head -n 1
  "$TT" preview "$OUT/$kind.png" "$OUT/${kind}_preview.png" > /dev/null
done

echo
echo "== a steep V-valley scene (the stability case of issue 3)"
"$SI" scenes/vvalley.yaml | sed -n '1,3p;5,12p'
echo
echo "Pictures: $OUT/*_preview.png. The servo demo (hapticd) arrives with issue 3."
