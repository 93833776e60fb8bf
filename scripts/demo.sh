#!/usr/bin/env bash
# The main job of the README: installs what is missing, builds, and runs Fissure on the bundled
# default — mesh the 1 × 1 × 0.05 m tile, solve the bundled load case (a 5 cm patch pressed on the
# top centre, tile resting on its four corners), write a result gmsh opens, then fracture the tile
# with the default material (ceramic-tile), write its fragments as closed meshes (GLB) and measure
# its visible pattern like an exemplar.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" >/dev/null
build_dir=${FISSURE_BUILD_DIR:-$root/build}
fissure=$build_dir/bin/fissure
out=$build_dir/demo
mkdir -p "$out"

case_file=$root/assets/demo/tile-corners.case
# shellcheck source=../assets/demo/tile-corners.case
source "$case_file"

echo "== fissure mesh $TILE --tets $TETS"
"$fissure" mesh "$TILE" --tets "$TETS" -o "$out/tile.msh"
echo "== fissure solve (direct)"
"$fissure" solve "$out/tile.msh" --E "$E" --nu "$NU" --rho "$RHO" \
  "${FIX[@]/#/--fix=}" "${LOAD[@]/#/--load=}" -o "$out/tile-result.msh"
echo "== fissure solve (modal, $MODES modes)"
"$fissure" solve "$out/tile.msh" --E "$E" --nu "$NU" --rho "$RHO" \
  "${FIX[@]/#/--fix=}" "${LOAD[@]/#/--load=}" --modes "$MODES" -o "$out/tile-result-modal.msh"
echo "== fissure modes"
"$fissure" modes "$out/tile.msh" --E "$E" --nu "$NU" --rho "$RHO" --count 10
echo "== fissure fracture (ceramic-tile, default supports and load)"
"$fissure" fracture "$out/tile.msh" --pattern "$out/tile-pattern.png" --stats "$out/tile-pattern.json" \
  --msh "$out/tile-fragments.msh" -o "$out/tile-fragments.glb"
echo "== fissure analyze (the drawing of the pattern, measured as a traced photo would be)"
"$fissure" analyze "$out/tile-pattern.png"
echo
echo "Wrote $out/tile-result.msh and $out/tile-result-modal.msh (stress) and $out/tile-fragments.msh"
echo "(fragment labels, crack-onset times): open them with gmsh. The crack pattern is"
echo "$out/tile-pattern.png, its statistics $out/tile-pattern.json. The fragments, one closed mesh"
echo "each, are $out/tile-fragments.glb: in Blender, File > Import > glTF 2.0 with Merge Vertices"
echo "ticked and Shading: Flat (README)."
