# Blender's side of the race (scripts/race-cell-fracture.sh): its Cell Fracture add-on breaks a
# 1 x 1 x 0.05 m tile into about N pieces from N seeded random points, and this reports the time
# of the operator, the pieces, how many are closed and the volume error, as one JSON line.
#
# Run: blender -b --factory-startup -t 0 --python scripts/race_cell_fracture.py -- N SEED
# (-t 0: all cores, as an artist runs it). The points are uniform in the tile, drawn by Python's
# random.Random(SEED); Cell Fracture's own jitter draws from `random`, seeded the same.
import json
import os
import random
import sys

import addon_utils
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_shards import add_seed_cloud, cell_fracture, shard_figures  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(argv) != 2:
    print("usage: blender -b --python race_cell_fracture.py -- PIECES SEED", file=sys.stderr)
    sys.exit(2)
pieces, seed = int(argv[0]), int(argv[1])
size = (1.0, 1.0, 0.05)

addon_utils.enable("object_fracture_cell", default_set=True)
bpy.ops.wm.read_factory_settings(use_empty=True)
addon_utils.enable("object_fracture_cell", default_set=True)

# The tile: a box centred on the origin.
bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, 0.0))
tile = bpy.context.active_object
tile.scale = size
bpy.ops.object.transform_apply(location=False, rotation=False, scale=True)

# The seed points: a child mesh of loose vertices (source 'VERT_CHILD').
rng = random.Random(seed)
points = [tuple((rng.random() - 0.5) * s for s in size) for _ in range(pieces)]
add_seed_cloud(tile, points, "seeds")
seconds, shards = cell_fracture([tile], seed)
closed, closed_as_made, volume = shard_figures(shards)
body = size[0] * size[1] * size[2]
print("RACE " + json.dumps({"tool": "blender_cell_fracture", "blender": bpy.app.version_string, "seeds": pieces,
                            "seed": seed, "seconds": seconds, "pieces": len(shards), "closed": closed,
                            "closed_as_made": closed_as_made,
                            "volume_err": abs(volume - body) / body}))
