"""Imports an exported fragments file into Blender as a user would, then reports what Blender
sees: one object per fragment, how many are closed (every edge manifold, none on a boundary),
the volume Blender computes, the materials and whether the node extras arrived as custom
properties. Prints one JSON line starting with RESULT, and OPEN lines naming open objects.

  blender -b --python scripts/blender_check_fragments.py -- fragments.glb   (or .gltf, .obj)

glTF is imported with "Merge Vertices" (the UV seams are split vertices, as glTF requires) and
flat shading: Debian 12's Blender 3.4 with numpy 1.24 fails on the default "Normals" shading
(np.bool was removed from numpy). OBJ is imported as it is:
its positions are written once each, so no merging is needed.

Blender's glTF importer needs numpy: `apt-get install blender python3-numpy` (scripts/race-setup.sh
does it; apt does not pull numpy in with Blender).
"""
import json
import sys

import bmesh
import bpy

path = sys.argv[sys.argv.index("--") + 1]
bpy.ops.wm.read_factory_settings(use_empty=True)
if path.lower().endswith(".obj"):
    bpy.ops.import_scene.obj(filepath=path)
else:
    bpy.ops.import_scene.gltf(filepath=path, merge_vertices=True, import_shading="FLAT")
objects = [o for o in bpy.context.scene.objects if o.type == "MESH"]
closed, volume, materials, with_extras = 0, 0.0, set(), 0
for o in objects:
    bm = bmesh.new()
    bm.from_mesh(o.data)
    bad = [e for e in bm.edges if not e.is_manifold or e.is_boundary]
    if bad:
        print("OPEN", o.name, len(bad), "edges")
    else:
        closed += 1
    volume += bm.calc_volume(signed=True)
    materials.update(m.name for m in o.data.materials if m)
    with_extras += "volume_m3" in o.keys()
    bm.free()
print("RESULT", json.dumps({"objects": len(objects), "closed": closed, "volume": volume,
                            "materials": sorted(materials), "with_extras": with_extras}))
