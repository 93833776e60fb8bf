"""What both Cell Fracture races (scripts/race_cell_fracture.py, scripts/race_street_cell_fracture.py)
do in Blender: give a body its seed points, break bodies with one Cell Fracture call (the same
options in both races), and measure the shards it made: how many are closed as made and after
Merge by Distance, and their summed volume. Imported by those scripts from inside Blender.

Cell Fracture leaves each cell's faces with their own copies of the seam vertices: as produced,
no shard is closed. An artist runs Merge by Distance; `closed` counts the shards closed after it
at 1e-6 m (Blender's default is 1e-4), `closed_as_made` before.
"""
import random
import time

import bmesh
import bpy


def add_seed_cloud(obj, points, name):
    """A child mesh of loose vertices at `points` (in obj's own frame), Cell Fracture's
    'VERT_CHILD' source. The parent inverse stays identity, so the points move with obj."""
    cloud = bpy.data.meshes.new(name)
    cloud.from_pydata(points, [], [])
    seeds = bpy.data.objects.new(name, cloud)
    bpy.context.collection.objects.link(seeds)
    seeds.parent = obj
    return seeds


def cell_fracture(objects, seed):
    """Breaks the mesh objects, each with its seed cloud, in one Cell Fracture call (margin 0, no
    noise, originals removed); its own jitter draws from `random`, seeded with `seed`.
    Returns (the operator's seconds, the new shard objects)."""
    bpy.ops.object.select_all(action="DESELECT")
    for obj in objects:
        obj.select_set(True)
    bpy.context.view_layer.objects.active = objects[0]
    random.seed(seed)
    before = set(bpy.data.objects)
    t0 = time.perf_counter()
    bpy.ops.object.add_fracture_cell_objects(source={"VERT_CHILD"}, source_limit=0, source_noise=0.0,
                                             margin=0.0, use_recenter=True, use_remove_original=True)
    seconds = time.perf_counter() - t0
    return seconds, [o for o in bpy.data.objects if o not in before and o.type == "MESH"]


def is_closed(bm):
    # Every edge has exactly two faces, wound consistently (Blender's own predicates).
    return bool(bm.edges) and all(e.is_manifold and e.is_contiguous for e in bm.edges)


def world_volume(obj):
    """The signed volume of a mesh object in world coordinates (m³)."""
    bm = bmesh.new()
    bm.from_mesh(obj.data)
    bm.transform(obj.matrix_world)
    volume = bm.calc_volume(signed=True)
    bm.free()
    return volume


def shard_figures(shards):
    """(closed, closed_as_made, summed world volume) of the shard objects."""
    closed = closed_as_made = 0
    volume = 0.0
    for o in shards:
        bm = bmesh.new()
        bm.from_mesh(o.data)
        bm.transform(o.matrix_world)
        closed_as_made += is_closed(bm)
        bmesh.ops.remove_doubles(bm, verts=bm.verts, dist=1e-6)
        closed += is_closed(bm)
        volume += bm.calc_volume(signed=True)
        bm.free()
    return closed, closed_as_made, volume
