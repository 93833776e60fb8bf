# Blender's side of the street race (scripts/race-street-cell-fracture.sh): Blender 3.4 opens the
# street scene as an artist would (its glTF importer), gives every body Fissure fractured as many
# seed points as Fissure made fragments of it (read from Fissure's --report), breaks them all with
# one Cell Fracture call ("fracture every object of this material"), and writes the scene as GLB.
# One JSON line reports the seconds of the import, the operator and the export, the pieces, how
# many are closed, and the volume error against the bodies' own volumes.
#
# Run: blender -b --factory-startup -t 0 --python scripts/race_street_cell_fracture.py -- \
#          SCENE.glb REPORT.json SEED OUT.glb
# (-t 0: all cores, as an artist runs it). A body's points are uniform in its mesh's bounding box,
# drawn by Python's random.Random(SEED) in the report's body order; Cell Fracture's own jitter
# draws from `random`, seeded the same.
import json
import os
import random
import sys
import time

import addon_utils
import bpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from blender_shards import add_seed_cloud, cell_fracture, shard_figures, world_volume  # noqa: E402

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
if len(argv) != 4:
    print("usage: blender -b --python race_street_cell_fracture.py -- SCENE.glb REPORT.json SEED OUT.glb",
          file=sys.stderr)
    sys.exit(2)
scene_path, report_path, seed, out_path = argv[0], argv[1], int(argv[2]), argv[3]

bpy.ops.wm.read_factory_settings(use_empty=True)
addon_utils.enable("object_fracture_cell", default_set=True)

t0 = time.perf_counter()
# Flat shading: Debian 12's Blender 3.4 with numpy 1.24 fails on the default "Normals" shading.
bpy.ops.import_scene.gltf(filepath=scene_path, import_shading="FLAT")
import_s = time.perf_counter() - t0

# The bodies Fissure fractured, by node name (the last part of the node path; the street's are
# unique), with the number of fragments Fissure made of each.
report = json.load(open(report_path))
targets = [(b["path"].rsplit("/", 1)[-1], b["fragments"]) for b in report["bodies"] if b["status"] == "fractured"]
rng = random.Random(seed)
bodies = []
for name, pieces in targets:
    obj = bpy.data.objects.get(name)
    if obj is None or obj.type != "MESH":
        print(f"race: the scene has no mesh object named {name!r}", file=sys.stderr)
        sys.exit(1)
    xs, ys, zs = zip(*(tuple(v.co) for v in obj.data.vertices))
    lo, hi = (min(xs), min(ys), min(zs)), (max(xs), max(ys), max(zs))
    points = [tuple(a + rng.random() * (b - a) for a, b in zip(lo, hi)) for _ in range(pieces)]
    add_seed_cloud(obj, points, name + "_seeds")
    bodies.append((obj, pieces, world_volume(obj)))

fracture_s, shards = cell_fracture([obj for obj, _, _ in bodies], seed)

# The seed clouds are no part of the scene an artist exports.
for o in [o for o in bpy.data.objects if o.name.endswith("_seeds")]:
    bpy.data.objects.remove(o, do_unlink=True)
t0 = time.perf_counter()
bpy.ops.export_scene.gltf(filepath=out_path, export_format="GLB")
export_s = time.perf_counter() - t0

closed, closed_as_made, volume = shard_figures(shards)
body_volume = sum(v for _, _, v in bodies)
print("RACE " + json.dumps({"tool": "blender_cell_fracture", "blender": bpy.app.version_string,
                            "bodies": len(bodies), "seeds": sum(p for _, p, _ in bodies), "seed": seed,
                            "import_s": import_s, "seconds": fracture_s, "export_s": export_s,
                            "pieces": len(shards), "closed": closed, "closed_as_made": closed_as_made,
                            "volume_err": abs(volume - body_volume) / body_volume}))
