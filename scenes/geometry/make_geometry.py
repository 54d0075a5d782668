#!/usr/bin/env python3
"""Writes the STL bodies of scenes/geometry (units: mm; scenes load them with scale = 0.001).

    python3 scenes/geometry/make_geometry.py [output_dir]

Only the standard library. Every body is closed, consistently oriented with outward normals
(counter-clockwise seen from outside); the script checks both before writing.
  beam_180x30x35.stl        calibration beam of the four-point bending test (seed sec. IV)
  filter_cake_shard.stl     irregular filter-cake plate shard, 35 mm thick, with a notch and a
                            through-hole: the non-convex parent body
  cube_10mm.stl             10 mm cube, binary;  cube_10mm_ascii.stl the same cube in ASCII
  sphere_r10mm.stl          icosphere (1280 faces) inscribed in a 10 mm radius sphere
  shell_r10_r6mm.stl        thick spherical shell: outer r = 10 mm, inner r = 6 mm (hollow)
  belt_to_chute_belt.stl    the conveyor of scenes/belt_to_chute.toml, in place: a 10 mm slab
                            3500 x 300 mm whose top face (z = 600 mm) the plates ride on; its head
                            end at x = 0
  belt_to_chute_chute.stl   the chute below it, in place: a 10 mm slab 400 mm wide whose top face
                            falls at 40 degrees along +x from (50, 500) mm to below the floor z = 0
  belt_to_chute_bin.stl     the bin on the floor that keeps the rolling fragments: four 10 mm walls
                            150 mm high around x in [-400, 1300] mm, y in [-250, 250] mm
"""
import math
import os
import struct
import sys


def box(lx, ly, lz):
    v = [(x, y, z) for z in (0.0, lz) for y in (0.0, ly) for x in (0.0, lx)]
    # vertex index = x + 2 y + 4 z; faces counter-clockwise seen from outside
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    f = []
    for a, b, c, d in quads:
        f += [(a, b, c), (a, c, d)]
    return v, f


def icosphere(radius, levels, inward=False):
    t = (1.0 + math.sqrt(5.0)) / 2.0
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        cache = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                p = [(v[a][k] + v[b][k]) / 2 for k in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                cache[key] = len(v) - 1
            return cache[key]

        g = []
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            g += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = g
    v = [tuple(radius * x for x in p) for p in v]
    if inward:
        f = [(a, c, b) for a, b, c in f]
    return v, f


def slab(origin, u, v, w):
    """Box spanned by the edge vectors u, v, w from corner `origin` (right-handed: (u x v) . w > 0)."""
    verts, faces = box(1.0, 1.0, 1.0)
    verts = [tuple(origin[k] + x * u[k] + y * v[k] + z * w[k] for k in range(3)) for x, y, z in verts]
    return verts, faces


def belt_to_chute_belt():
    return slab((-3500.0, -150.0, 590.0), (3500.0, 0.0, 0.0), (0.0, 300.0, 0.0), (0.0, 0.0, 10.0))


def belt_to_chute_chute():
    angle = math.radians(40.0)
    top, length, width, thickness = (50.0, 500.0), 820.0, 400.0, 10.0
    down = (math.cos(angle), 0.0, -math.sin(angle))   # along the chute, downhill
    n = (math.sin(angle), 0.0, math.cos(angle))       # the face the plates land on looks along n
    origin = (top[0] - thickness * n[0], -width / 2, top[1] - thickness * n[2])
    return slab(origin, tuple(length * c for c in down), (0.0, width, 0.0), tuple(thickness * c for c in n))


def belt_to_chute_bin():
    x0, x1, y0, y1, height, t = -400.0, 1300.0, -250.0, 250.0, 150.0, 10.0
    return merge(slab((x0 - t, y0 - t, 0.0), (t, 0.0, 0.0), (0.0, y1 - y0 + 2 * t, 0.0), (0.0, 0.0, height)),
                 slab((x1, y0 - t, 0.0), (t, 0.0, 0.0), (0.0, y1 - y0 + 2 * t, 0.0), (0.0, 0.0, height)),
                 slab((x0, y0 - t, 0.0), (x1 - x0, 0.0, 0.0), (0.0, t, 0.0), (0.0, 0.0, height)),
                 slab((x0, y1, 0.0), (x1 - x0, 0.0, 0.0), (0.0, t, 0.0), (0.0, 0.0, height)))


def merge(*meshes):
    verts, faces = [], []
    for v, f in meshes:
        base = len(verts)
        verts += v
        faces += [tuple(base + i for i in t) for t in f]
    return verts, faces


def shard_plate():
    """Irregular plate shard: star-shaped outline (random-looking but fixed harmonics) with a
    V-notch, an off-centre circular through-hole, 35 mm thick with a gently undulating top."""
    n = 180          # points around
    rings = 6        # rings between hole and outline on top and bottom faces
    hole_centre, hole_radius = (4.0, -3.0), 9.0

    def outline(theta):
        r = 42.0 + 5.0 * math.sin(3 * theta + 0.4) + 3.0 * math.cos(5 * theta + 1.1) + 1.5 * math.sin(7 * theta)
        notch_at, notch_half = 0.9, 0.22   # a V-notch cut 14 mm deep
        d = abs(math.atan2(math.sin(theta - notch_at), math.cos(theta - notch_at)))
        if d < notch_half:
            r -= 14.0 * (1.0 - d / notch_half)
        return r

    def hole(theta):
        # ray from the origin (inside the hole) to the hole circle
        cx, cy = hole_centre
        ux, uy = math.cos(theta), math.sin(theta)
        b = ux * cx + uy * cy
        return b + math.sqrt(b * b - (cx * cx + cy * cy - hole_radius ** 2))

    def top(x, y):
        return 35.0 + 1.2 * math.sin(x / 13.0) * math.cos(y / 17.0) - 0.015 * x

    verts, faces = [], []
    index = {}
    for side in (0, 1):   # 0 bottom, 1 top
        for ring in range(rings + 1):
            for i in range(n):
                th = 2 * math.pi * i / n
                s = ring / rings
                r = (1 - s) * hole(th) + s * outline(th)
                x, y = r * math.cos(th), r * math.sin(th)
                index[(side, ring, i)] = len(verts)
                verts.append((x, y, top(x, y) if side else 0.0))
    q = []
    for ring in range(rings):
        for i in range(n):
            j = (i + 1) % n
            a, b = (ring, i), (ring, j)
            c, d = (ring + 1, j), (ring + 1, i)
            # a-b runs along +theta, b-c outward: a,b,c,d is clockwise seen from +z (bottom face)
            q.append([index[(1,) + p] for p in (a, d, c, b)])
            q.append([index[(0,) + p] for p in (a, b, c, d)])
    for i in range(n):
        j = (i + 1) % n
        # outer wall faces outward, hole wall faces the hole axis
        q.append([index[(0, rings, i)], index[(0, rings, j)], index[(1, rings, j)], index[(1, rings, i)]])
        q.append([index[(0, 0, j)], index[(0, 0, i)], index[(1, 0, i)], index[(1, 0, j)]])
    for a, b, c, d in q:
        faces += [(a, b, c), (a, c, d)]
    return verts, faces


def signed_volume(v, f):
    s = 0.0
    for a, b, c in f:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = v[a], v[b], v[c]
        s += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    return s / 6.0


def check(name, v, f):
    edges = {}
    for t in f:
        for k in range(3):
            e = (t[k], t[(k + 1) % 3])
            edges[e] = edges.get(e, 0) + 1
    for (a, b), count in edges.items():
        if count != 1 or edges.get((b, a), 0) != 1:
            raise SystemExit(f"{name}: edge {a}-{b} is open, repeated or misoriented")
    vol = signed_volume(v, f)
    if vol <= 0:
        raise SystemExit(f"{name}: signed volume {vol} <= 0 (inverted normals)")
    return vol


def normal(v, t):
    a, b, c = (v[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    w = [c[k] - a[k] for k in range(3)]
    n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
    length = math.sqrt(sum(x * x for x in n)) or 1.0
    return [x / length for x in n]


def write_binary(path, v, f):
    with open(path, "wb") as out:
        out.write(b"shard make_geometry.py".ljust(80, b" "))
        out.write(struct.pack("<I", len(f)))
        for t in f:
            out.write(struct.pack("<12fH", *normal(v, t), *[x for i in t for x in v[i]], 0))


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def write_ascii(path, v, f, name="shard"):
    with open(path, "w") as out:
        out.write(f"solid {name}\n")
        for t in f:
            out.write("  facet normal %.9g %.9g %.9g\n    outer loop\n" % tuple(normal(v, t)))
            for i in t:
                out.write("      vertex %.9g %.9g %.9g\n" % tuple(f32(x) for x in v[i]))
            out.write("    endloop\n  endfacet\n")
        out.write(f"endsolid {name}\n")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    bodies = {
        "beam_180x30x35.stl": box(180.0, 30.0, 35.0),
        "filter_cake_shard.stl": shard_plate(),
        "cube_10mm.stl": box(10.0, 10.0, 10.0),
        "sphere_r10mm.stl": icosphere(10.0, 3),
        "shell_r10_r6mm.stl": merge(icosphere(10.0, 3), icosphere(6.0, 3, inward=True)),
        "belt_to_chute_belt.stl": belt_to_chute_belt(),
        "belt_to_chute_chute.stl": belt_to_chute_chute(),
        "belt_to_chute_bin.stl": belt_to_chute_bin(),
    }
    for name, (v, f) in bodies.items():
        vol = check(name, v, f)
        write_binary(os.path.join(out, name), v, f)
        print(f"{name}: {len(v)} vertices, {len(f)} faces, volume {vol:.6g} mm^3")
    v, f = bodies["cube_10mm.stl"]
    write_ascii(os.path.join(out, "cube_10mm_ascii.stl"), v, f, "cube_10mm")


if __name__ == "__main__":
    main()
