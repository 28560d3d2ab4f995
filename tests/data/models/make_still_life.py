#!/usr/bin/env python3
"""Writes still_life.obj, still_life.mtl and still_life_tiles.png: a small OBJ model with its
materials, for images/obj_model.png (docs/models.md) and the tests. Our own geometry (boxes and
icospheres), made here; no external model.

    python3 tests/data/models/make_still_life.py [DIR]     (default: this script's directory)

Materials, one per MTL rule of rtweekend/io/obj_model.h: a table top of tiles (map_Kd), a
Lambertian floor, glazed clay (Ks, Ns: blinn_phong), glass (illum 7, Ni 1.5), a rough copper
(PBR Pm, Pr: metal_roughness), and a ceiling lamp (Ke)."""
import math, os, struct, sys, zlib

out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
verts, uvs, normals, lines = [], [], [], []

def box(lo, hi, mtl, textured=False):
    lines.append(f"usemtl {mtl}")
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    corners = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
               (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    base = len(verts)
    verts.extend(corners)
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (3, 7, 6, 2), (0, 4, 7, 3), (1, 2, 6, 5)]
    if textured:  # the top face (y = y1) carries the tiles: u along x, v along z
        t = len(uvs)
        uvs.extend([(0, 0), (0, 1), (1, 1), (1, 0)])
    for k, f in enumerate(faces):
        if textured and k == 3:
            lines.append("f " + " ".join(f"{base + i + 1}/{t + j + 1}" for j, i in enumerate(f)))
        else:
            lines.append("f " + " ".join(str(base + i + 1) for i in f))

def icosphere(centre, r, mtl, level=2):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        cache, nf = {}, []
        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                p = [(v[a][i] + v[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                cache[key] = len(v) - 1
            return cache[key]
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    lines.append(f"usemtl {mtl}")
    base, nbase = len(verts), len(normals)
    verts.extend(tuple(centre[i] + r * p[i] for i in range(3)) for p in v)
    normals.extend(v)  # a unit sphere's points are its normals: smooth shading
    for a, b, c in f:
        lines.append(" ".join(["f"] + [f"{base + i + 1}//{nbase + i + 1}" for i in (a, b, c)]))

box((-3, -0.1, -3), (3, 0, 3), "floor")
box((-1.2, 0, -0.8), (1.2, 0.8, 0.8), "tiles", textured=True)
icosphere((-0.65, 1.15, 0.1), 0.35, "glass")
icosphere((0.1, 1.1, -0.25), 0.3, "copper")
icosphere((0.75, 1.05, 0.3), 0.25, "clay")
box((-0.9, 2.6, -0.9), (0.9, 2.62, 0.9), "lamp")

with open(os.path.join(out, "still_life.obj"), "w") as o:
    o.write("# A still life made by make_still_life.py (rtweekend's tests/data/models)\nmtllib still_life.mtl\n")
    o.writelines(f"v {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in verts)
    o.writelines(f"vt {u} {v}\n" for u, v in uvs)
    o.writelines(f"vn {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in normals)
    o.writelines(l + "\n" for l in lines)

with open(os.path.join(out, "still_life.mtl"), "w") as o:
    o.write("""# Materials of still_life.obj (make_still_life.py)
newmtl floor
Kd 0.55 0.55 0.55
newmtl tiles
Kd 0.7 0.7 0.7
map_Kd still_life_tiles.png
newmtl clay
Kd 0.6 0.2 0.08
Ks 0.3 0.3 0.3
Ns 60
newmtl glass
Kd 0 0 0
Ni 1.5
illum 7
newmtl copper
Kd 0.955 0.638 0.538
Pm 1
Pr 0.35
newmtl lamp
Kd 0 0 0
Ke 12 11 9
""")

def png(path, w, h, pixel):
    raw = b"".join(b"\0" + bytes(c for x in range(w) for c in pixel(x, y)) for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    with open(path, "wb") as o:
        o.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))

# 6 x 4 tiles with grout lines: terracotta and cream.
png(os.path.join(out, "still_life_tiles.png"), 96, 64,
    lambda x, y: (60, 55, 50) if x % 16 < 1 or y % 16 < 1 else
    ((190, 90, 50) if (x // 16 + y // 16) % 2 else (225, 210, 180)))
