#!/bin/bash
# Regenerates the study surfaces' contact sheets in docs/study/ (docs/study.md "Shipped study
# surfaces"): each scene drawn headless by visual-client in its own representation, then tiled.
# usage: docs/study/make_pictures.sh [BUILD_DIR]   (default build; run from the repository root)
set -euo pipefail
if [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then sed -n 2,4p "$0"; exit 0; fi
BUILD=${1:-build}
VC="$BUILD/clients/visual/visual-client"
[ -x "$VC" ] || { echo "no $VC: build the visual-client target first" >&2; exit 1; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
shot() {  # scene file, mode, output
  "$VC" --scene "$1" --mode "$2" --screenshot "$3" --size 256x160 --distance 0.22 --elevation 50 \
        --target 0.0,0.02 --quiet
}
study1=()
for s in bricks_red bricks_concrete bricks_marble porcelain_glazed porcelain_crazed \
         metal_steel_brushed metal_aluminium_knurled metal_copper_hammered wood_oak wood_pine; do
  shot "scenes/study/study1_$s.yaml" normal "$TMP/1_$s.png"
  study1+=("$TMP/1_$s.png")
done
python3 docs/study/contact_sheet.py docs/study/study1_surfaces.png 5 "${study1[@]}"
relief=() normal=()
for s in wood_walnut wood_plank stone_granite stone_marble ceramic_tile metal_brass_knurled; do
  shot "scenes/study/study2_${s}_relief.yaml" relief "$TMP/2r_$s.png"
  shot "scenes/study/study2_${s}_normal.yaml" normal "$TMP/2n_$s.png"
  relief+=("$TMP/2r_$s.png")
  normal+=("$TMP/2n_$s.png")
done
python3 docs/study/contact_sheet.py docs/study/study2_relief.png 3 "${relief[@]}"
python3 docs/study/contact_sheet.py docs/study/study2_normal.png 3 "${normal[@]}"
echo "wrote docs/study/study1_surfaces.png, docs/study/study2_relief.png, docs/study/study2_normal.png"
