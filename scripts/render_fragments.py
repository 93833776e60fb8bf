#!/usr/bin/env python3
"""Renders the fragments of `fissure fracture --msh` output as a shaded PNG: every fragment's
boundary (tet faces on the body's surface or between two fragments) in its own colour, seen from
above at an angle, the fragments pushed apart from the body's centre (an exploded view) so the
cracks show as gaps. Standard library only (no numpy or PIL on the build machines): a z-buffer
rasteriser and zlib for the PNG. Labels are per tet, so crack faces are the tets' faces, not the
crack surfaces (the fragment meshing of the next issue clips them exactly).

  scripts/render_fragments.py labelled.msh out.png [--size 640] [--explode 0.08]
      [--elevation 50] [--azimuth 30]
"""
import argparse
import colorsys
import math
import struct
import zlib


def read_msh(path):
    """Nodes {tag: (x, y, z)}, tets [(tag, (n1..n4))], and the 'fragment' element view {tag: label}."""
    nodes, tets, fragment = {}, [], {}
    with open(path) as f:
        lines = iter(f.read().split("\n"))
    for line in lines:
        if line == "$Nodes":
            blocks = int(next(lines).split()[0])
            for _ in range(blocks):
                count = int(next(lines).split()[3])
                tags = [int(next(lines)) for _ in range(count)]
                for t in tags:
                    nodes[t] = tuple(float(v) for v in next(lines).split()[:3])
        elif line == "$Elements":
            blocks = int(next(lines).split()[0])
            for _ in range(blocks):
                _, _, kind, count = (int(v) for v in next(lines).split())
                for _ in range(count):
                    v = [int(x) for x in next(lines).split()]
                    if kind == 4:
                        tets.append((v[0], tuple(v[1:5])))
        elif line == "$ElementData":
            names = [next(lines).strip('"') for _ in range(int(next(lines)))]
            for _ in range(int(next(lines))):
                next(lines)
            ints = [int(next(lines)) for _ in range(int(next(lines)))]
            values = {}
            for _ in range(ints[2]):
                tag, value = next(lines).split()[:2]
                values[int(tag)] = float(value)
            if names and names[0] == "fragment":
                fragment = values
    return nodes, tets, fragment


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def fragment_faces(nodes, tets, fragment):
    """(node tags, label, the tet's fourth node) of every face on the surface or between fragments."""
    by_key = {}
    for tag, n in tets:
        label = int(fragment.get(tag, 0))
        for i in range(4):
            face = tuple(n[j] for j in range(4) if j != i)
            by_key.setdefault(tuple(sorted(face)), []).append((face, label, n[i]))
    out = []
    for sides in by_key.values():
        if len(sides) == 1 or sides[0][1] != sides[1][1]:
            out.extend(sides)
    return out


def render(nodes, tets, fragment, size, explode, elevation, azimuth):
    faces = fragment_faces(nodes, tets, fragment)
    pts = list(nodes.values())
    lo = [min(p[i] for p in pts) for i in range(3)]
    hi = [max(p[i] for p in pts) for i in range(3)]
    centre = tuple(0.5 * (lo[i] + hi[i]) for i in range(3))
    extent = max(hi[i] - lo[i] for i in range(3))
    # Fragment centroids, for the exploded view.
    sums = {}
    for tag, n in tets:
        label = int(fragment.get(tag, 0))
        s = sums.setdefault(label, [0.0, 0.0, 0.0, 0])
        for v in n:
            for i in range(3):
                s[i] += nodes[v][i] / 4.0
        s[3] += 1
    shift = {}
    for label, s in sums.items():
        c = (s[0] / s[3], s[1] / s[3], s[2] / s[3])
        d = sub(c, centre)
        length = math.sqrt(dot(d, d)) or 1.0
        shift[label] = tuple(explode * extent * d[i] / length * min(1.0, 2.0 * length / extent) for i in range(3))
    el, az = math.radians(elevation), math.radians(azimuth)
    # Camera looking down at the body from elevation `el`, turned by `az` about z.
    forward = (-math.cos(el) * math.cos(az), -math.cos(el) * math.sin(az), -math.sin(el))
    right = (-math.sin(az), math.cos(az), 0.0)
    upv = cross(right, forward)
    light = (0.3, -0.4, 0.87)
    projected = []
    for face, label, opposite in faces:
        p = [tuple(nodes[v][i] + shift[label][i] for i in range(3)) for v in face]
        normal = cross(sub(p[1], p[0]), sub(p[2], p[0]))
        if dot(normal, sub(nodes[opposite], nodes[face[0]])) > 0:
            normal = (-normal[0], -normal[1], -normal[2])  # outward from its tet
        length = math.sqrt(dot(normal, normal)) or 1.0
        normal = tuple(c / length for c in normal)
        if dot(normal, forward) >= 0:
            continue  # back-facing
        shade = 0.35 + 0.65 * max(0.0, dot(normal, light) / math.sqrt(dot(light, light)))
        hue = (label * 0.61803398875) % 1.0
        rgb = colorsys.hsv_to_rgb(hue, 0.55, 0.95 * shade)
        screen = []
        for q in p:
            d = sub(q, centre)
            screen.append((dot(d, right), dot(d, upv), dot(d, forward)))
        projected.append((screen, tuple(int(255 * c) for c in rgb)))
    xs = [s[0] for f, _ in projected for s in f]
    ys = [s[1] for f, _ in projected for s in f]
    span = max(max(xs) - min(xs), max(ys) - min(ys)) * 1.04
    cx, cy = 0.5 * (max(xs) + min(xs)), 0.5 * (max(ys) + min(ys))
    width = size
    height = max(16, int(size * (max(ys) - min(ys)) * 1.04 / span) + 8)
    scale = size / span
    depth = [float("inf")] * (width * height)
    image = bytearray(b"\xff" * (3 * width * height))
    for screen, rgb in projected:
        v = [((x - cx) * scale + width / 2, height / 2 - (y - cy) * scale, z) for x, y, z in screen]
        x0, x1 = max(0, int(min(p[0] for p in v))), min(width - 1, int(max(p[0] for p in v)) + 1)
        y0, y1 = max(0, int(min(p[1] for p in v))), min(height - 1, int(max(p[1] for p in v)) + 1)
        (ax, ay, az_), (bx, by, bz), (qx, qy, qz) = v
        area = (bx - ax) * (qy - ay) - (qx - ax) * (by - ay)
        if area == 0:
            continue
        for y in range(y0, y1 + 1):
            for x in range(x0, x1 + 1):
                px, py = x + 0.5, y + 0.5
                w0 = ((bx - px) * (qy - py) - (qx - px) * (by - py)) / area
                w1 = ((qx - px) * (ay - py) - (ax - px) * (qy - py)) / area
                w2 = 1.0 - w0 - w1
                if w0 < 0 or w1 < 0 or w2 < 0:
                    continue
                z = w0 * az_ + w1 * bz + w2 * qz
                i = y * width + x
                if z < depth[i]:
                    depth[i] = z
                    image[3 * i:3 * i + 3] = bytes(rgb)
    return width, height, image, len(sums)


def write_png(path, width, height, rgb):
    rows = b"".join(b"\x00" + bytes(rgb[3 * width * y:3 * width * (y + 1)]) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", zlib.compress(rows, 9)))
        f.write(chunk(b"IEND", b""))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("msh")
    parser.add_argument("png")
    parser.add_argument("--size", type=int, default=640)
    parser.add_argument("--explode", type=float, default=0.08, help="push-apart, fraction of the body's extent")
    parser.add_argument("--elevation", type=float, default=50.0, help="degrees above the horizon")
    parser.add_argument("--azimuth", type=float, default=30.0, help="degrees about z")
    args = parser.parse_args()
    nodes, tets, fragment = read_msh(args.msh)
    width, height, image, count = render(nodes, tets, fragment, args.size, args.explode, args.elevation, args.azimuth)
    write_png(args.png, width, height, image)
    print(f"{args.png}: {count} fragments, {width}x{height}")


if __name__ == "__main__":
    main()
