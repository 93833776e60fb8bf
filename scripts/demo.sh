#!/usr/bin/env bash
# The main job of the README: installs what is missing, builds, and runs Fissure on the bundled
# defaults. First the bundled street scene end to end (assets/scenes/street.glb): every sidewalk
# slab and the curb fractured with the bundled concrete, each slab with its own seed, the road
# left as it is, the whole scene written as one GLB that Blender opens. Then one body step by
# step: mesh the 1 × 1 × 0.05 m tile, solve the bundled load case (a 5 cm patch pressed on the
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

# Age 50: every slab broken, into 2 to 30 pieces (at age 12, 10 of the 24 stay whole: the
# pieces they seemed to have were dust, docs/fragments.md).
echo "== fissure scene fracture assets/scenes/street.glb (sidewalk slabs and curb: concrete)"
"$fissure" scene fracture "$root/assets/scenes/street.glb" --assign concrete=concrete --assign curb=concrete --age 50 \
  --report "$out/street-report.json" -o "$out/street-fractured.glb"

if command -v blender >/dev/null; then
  echo "== Blender opens it (scripts/blender_check_scene.py)"
  blender -b --python "$root/scripts/blender_check_scene.py" -- "$out/street-fractured.glb" \
    "$root/assets/scenes/street.glb" 2>/dev/null | grep -E '^(RESULT|OPEN|MISPLACED|LOST|MOVED|OUTSIDE|UNFILLED|COUNT)' ||
    echo "Blender's check reported a problem, or Blender could not run it (its glTF importer needs python3-numpy)"
fi

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
echo "Wrote $out/street-fractured.glb, the street with every slab and the curb broken (each body a"
echo "node holding its fragments), and $out/street-report.json (per body: fragments, seed, timings)."
echo "Open it in Blender: File > Import > glTF 2.0, Merge Vertices ticked, Shading: Flat (README)."
echo "Wrote $out/tile-result.msh and $out/tile-result-modal.msh (stress) and $out/tile-fragments.msh"
echo "(fragment labels, crack-onset times): open them with gmsh. The crack pattern is"
echo "$out/tile-pattern.png, its statistics $out/tile-pattern.json. The fragments, one closed mesh"
echo "each, are $out/tile-fragments.glb: in Blender, File > Import > glTF 2.0 with Merge Vertices"
echo "ticked and Shading: Flat (README)."
