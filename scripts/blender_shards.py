"""What both Cell Fracture races (scripts/race_cell_fracture.py, scripts/race_street_cell_fracture.py)
measure on the shards Blender made: how many are closed as made and after Merge by Distance, and
their summed volume. Imported by those scripts from inside Blender (bmesh is Blender's).

Cell Fracture leaves each cell's faces with their own copies of the seam vertices: as produced,
no shard is closed. An artist runs Merge by Distance; `closed` counts the shards closed after it
at 1e-6 m (Blender's default is 1e-4), `closed_as_made` before.
"""
import bmesh


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
