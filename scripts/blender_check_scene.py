"""Imports a scene Fissure exported (`fissure scene fracture -o scene.glb`) into Blender as a user
would and checks it against the file itself: every glTF node became one Blender object with its
name (Blender adds .001, ... to repeated names such as fragment_000) and its parent's name, every
mesh sits where the file's node hierarchy puts it (the centre of its bounding box in world
coordinates, to 1e-4 m), and every fragment is closed (each edge shared by exactly two faces
once Merge Vertices has rejoined the UV seams). Prints one JSON line starting with RESULT and
a line per problem; exits non-zero when there is one.

Given the scene it was made from as well, it checks the export against that scene too: every
mesh node of the original is an object of the same name under the same parent; an untouched one
sits where it sat (bounding-box centre to 1e-4 m); a fractured one's fragments lie inside its
original bounding box and together fill it (to 1e-4 m and 0.1 % of its diagonal).

  blender -b --python scripts/blender_check_scene.py -- scene.glb [original.glb]

Shading is Flat: Debian 12's Blender 3.4 with numpy 1.24 fails on the default "Normals" shading.

Blender's glTF importer needs numpy: `apt-get install blender python3-numpy` (scripts/race-setup.sh
does it; apt does not pull numpy in with Blender).
"""
import json
import re
import struct
import sys

import bmesh
import bpy
import mathutils

args = sys.argv[sys.argv.index("--") + 1:]
path = args[0]
original_path = args[1] if len(args) > 1 else None


def read_gltf_json(path):
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        length, kind = struct.unpack_from("<II", data, 12)
        return json.loads(data[20:20 + length])
    return json.loads(data)


def parents_of(nodes):
    parent = {}
    for i, n in enumerate(nodes):
        for c in n.get("children", []):
            parent[c] = i
    return parent


def local_matrix(n):
    if "matrix" in n:
        m = n["matrix"]
        return mathutils.Matrix([[m[c * 4 + r] for c in range(4)] for r in range(4)])
    t = n.get("translation", [0, 0, 0])
    return mathutils.Matrix.Translation(t)


def world_matrix(nodes, parent, i):
    m = local_matrix(nodes[i])
    while i in parent:
        i = parent[i]
        m = local_matrix(nodes[i]) @ m
    return m


# glTF is +Y up, Blender +Z up: the importer maps (x, y, z) to (x, -z, y).
to_blender = mathutils.Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))


def mesh_nodes(gltf):
    """(name, parent name, world bbox low, high in Blender's frame) per node with a mesh."""
    nodes = gltf["nodes"]
    parent = parents_of(nodes)
    out = []
    for i, n in enumerate(nodes):
        if "mesh" not in n:
            continue
        accessor = gltf["accessors"][gltf["meshes"][n["mesh"]]["primitives"][0]["attributes"]["POSITION"]]
        lo, hi = accessor["min"], accessor["max"]
        m = to_blender @ world_matrix(nodes, parent, i)
        corners = [(m @ mathutils.Vector((x, y, z, 1))).to_3d() for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
        low = mathutils.Vector([min(c[k] for c in corners) for k in range(3)])
        high = mathutils.Vector([max(c[k] for c in corners) for k in range(3)])
        out.append((n["name"], nodes[parent[i]]["name"] if i in parent else None, low, high))
    return out


gltf = read_gltf_json(path)
nodes = gltf["nodes"]
expected = [(name, parent_name, (low + high) / 2) for name, parent_name, low, high in mesh_nodes(gltf)]

bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=path, merge_vertices=True, import_shading="FLAT")
base = lambda name: re.sub(r"\.\d{3}$", "", name)
objects = list(bpy.context.scene.objects)
problems = []
if len(objects) != len(nodes):
    problems.append(f"COUNT {len(objects)} Blender objects for {len(nodes)} glTF nodes")

meshes = {}
closed, fragments = 0, 0
boxes = {}  # id(object) -> world AABB
for o in objects:
    if o.type != "MESH":
        continue
    corners = [o.matrix_world @ mathutils.Vector(c) for c in o.bound_box]
    centre = sum(corners, mathutils.Vector()) / 8
    boxes[o.name] = (mathutils.Vector([min(c[k] for c in corners) for k in range(3)]),
                     mathutils.Vector([max(c[k] for c in corners) for k in range(3)]))
    meshes.setdefault(base(o.name), []).append((base(o.parent.name) if o.parent else None, centre))
    if base(o.name).startswith("fragment_"):
        fragments += 1
        bm = bmesh.new()
        bm.from_mesh(o.data)
        if all(e.is_manifold and not e.is_boundary for e in bm.edges):
            closed += 1
        else:
            problems.append(f"OPEN {o.name} (under {o.parent.name if o.parent else '-'})")
        bm.free()

placed = 0
for name, parent_name, centre in expected:
    candidates = meshes.get(name, [])
    match = next((k for k, (p, c) in enumerate(candidates) if p == parent_name and (c - centre).length < 1e-4), None)
    if match is None:
        problems.append(f"MISPLACED {name} under {parent_name}: no Blender object there (expected centre {tuple(round(x, 5) for x in centre)})")
    else:
        candidates.pop(match)
        placed += 1

checked, broken = 0, 0
if original_path:
    for name, parent_name, low, high in mesh_nodes(read_gltf_json(original_path)):
        body = [o for o in objects if base(o.name) == name and (base(o.parent.name) if o.parent else None) == parent_name]
        if not body:
            problems.append(f"LOST {name} under {parent_name}: in the original, not in the export")
            continue
        o = body[0]
        checked += 1
        pieces = [c for c in o.children if c.type == "MESH" and base(c.name).startswith("fragment_")]
        if not pieces:
            centre = (boxes[o.name][0] + boxes[o.name][1]) / 2 if o.name in boxes else None
            if centre is None or (centre - (low + high) / 2).length > 1e-4:
                problems.append(f"MOVED {o.name}: not where the original has it")
            continue
        broken += 1
        tolerance = max(1e-4, 1e-3 * (high - low).length)
        union_low = mathutils.Vector([min(boxes[c.name][0][k] for c in pieces) for k in range(3)])
        union_high = mathutils.Vector([max(boxes[c.name][1][k] for c in pieces) for k in range(3)])
        for c in pieces:
            lo, hi = boxes[c.name]
            if any(lo[k] < low[k] - tolerance or hi[k] > high[k] + tolerance for k in range(3)):
                problems.append(f"OUTSIDE {c.name} of {o.name}: beyond the original body's bounding box")
        if (union_low - low).length > tolerance or (union_high - high).length > tolerance:
            problems.append(f"UNFILLED {o.name}: its fragments do not fill the original body's bounding box")

for p in problems[:50]:
    print(p)
print("RESULT " + json.dumps({"file": path, "nodes": len(nodes), "objects": len(objects), "meshes": len(expected),
                              "placed": placed, "fragments": fragments, "closed": closed, "original_bodies": checked, "fractured": broken,
                              "problems": len(problems)}))
sys.exit(1 if problems else 0)
