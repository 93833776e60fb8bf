#!/usr/bin/env bash
# Regenerates the demo scenes of assets/scenes/ with Fissure's own code (scene/demo_scenes.hpp):
# street.glb (24 sidewalk slabs, a curb, a road section; scene materials concrete, curb,
# asphalt) and bathroom.glb (floor and wall tiles, a basin made as a surface of revolution, a
# mirror; ceramic-tile, porcelain, glass). A test checks that the committed files are what the
# code writes, so run this after changing demo_scenes.cpp.
#   scripts/make-demo-scenes.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
fissure=${1:-${FISSURE_BUILD_DIR:-$root/build}}/bin/fissure
for scene in street bathroom; do
  "$fissure" scene demo "$scene" -o "$root/assets/scenes/$scene.glb"
  "$fissure" scene info -q "$root/assets/scenes/$scene.glb" | head -1
done
