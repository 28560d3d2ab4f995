#!/usr/bin/env python3
"""Writes showcase.glb, the glTF model images/gltf_model.png shows (docs/models.md): a checkered
floor, three gold spheres from smooth to rough (three meshes sharing one sphere's accessors),
a glass sphere (KHR_materials_transmission and _ior), a hammered copper block (a normal map), two blue plastic balls (one mesh placed by two nodes: instances), an emissive
panel overhead (KHR_materials_emissive_strength), a point light (KHR_lights_punctual) and a camera.
Everything is made here, by this script; it is released with the project.

    python3 tests/data/models/make_gltf_showcase.py tests/data/models/showcase.glb
    python3 tests/data/models/make_gltf_showcase.py /tmp/big.glb --sphere-triangles 1000000
    python3 tests/data/models/make_gltf_showcase.py /tmp/big.obj --sphere-triangles 1000000
        (one sphere of about that many triangles, as a GLB or the same as an OBJ with an MTL of the
        same material, for BENCHMARKS.md's load times)
"""
import json
import math
import struct
import sys
import zlib


def png(width, height, rgb):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    rows = b"".join(b"\0" + bytes(rgb[y * width * 3:(y + 1) * width * 3]) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


class Glb:
    def __init__(self):
        self.bin = bytearray()
        self.views, self.accessors = [], []

    def view(self, data):
        while len(self.bin) % 4:
            self.bin += b"\0"
        self.views.append({"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.views) - 1

    def accessor(self, fmt, values, component, kind, count, minmax=False):
        acc = {"bufferView": self.view(struct.pack("<%d%s" % (len(values), fmt), *values)),
               "componentType": component, "count": count, "type": kind}
        if minmax:  # POSITION accessors carry their bounds, as glTF requires
            acc["min"] = [min(values[i::3]) for i in range(3)]
            acc["max"] = [max(values[i::3]) for i in range(3)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def mesh(self, positions, normals, uvs, indices):
        n = len(positions) // 3
        return {"POSITION": self.accessor("f", positions, 5126, "VEC3", n, True),
                "NORMAL": self.accessor("f", normals, 5126, "VEC3", n),
                "TEXCOORD_0": self.accessor("f", uvs, 5126, "VEC2", n)}, \
            self.accessor("I", indices, 5125, "SCALAR", len(indices))


def sphere(segments, rings):
    pos, nrm, uv, idx = [], [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            pos += n
            nrm += n
            uv += [s / segments, r / rings]
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            if r > 0:
                idx += [a, a + 1, b]
            if r < rings - 1:
                idx += [a + 1, b + 1, b]
    return pos, nrm, uv, idx


def box(lo, hi):
    pos, nrm, uv, idx = [], [], [], []
    for axis in range(3):
        for side in (0, 1):
            n = [0, 0, 0]
            n[axis] = 1 if side else -1
            u_axis, v_axis = (axis + 1) % 3, (axis + 2) % 3
            base = len(pos) // 3
            for du, dv in [(0, 0), (1, 0), (1, 1), (0, 1)]:
                p = [0, 0, 0]
                p[axis] = hi[axis] if side else lo[axis]
                p[u_axis] = hi[u_axis] if du else lo[u_axis]
                p[v_axis] = hi[v_axis] if dv else lo[v_axis]
                pos += p
                nrm += n
                uv += [du, dv]
            quad = [base, base + 1, base + 2, base, base + 2, base + 3]
            if not side:
                quad = [base, base + 2, base + 1, base, base + 3, base + 2]
            idx += quad
    return pos, nrm, uv, idx


def write(path, model, g):
    js = json.dumps(model, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    binary = bytes(g.bin) + b"\0" * (-len(g.bin) % 4)
    total = 12 + 8 + len(js) + 8 + len(binary)
    with open(path, "wb") as f:
        f.write(b"glTF" + struct.pack("<II", 2, total) + struct.pack("<I", len(js)) + b"JSON" + js +
                struct.pack("<I", len(binary)) + b"BIN\0" + binary)


def big(path, triangles):
    g = Glb()
    rings = max(2, int(math.sqrt(triangles / 4)))  # 2 rings segments, two triangles each
    pos, nrm, uv, idx = sphere(2 * rings, rings)
    if path.endswith(".obj"):
        mtl = path[:-4] + ".mtl"
        with open(mtl, "w") as f:
            f.write("newmtl gold\nKd 0.9 0.6 0.3\nPm 1\nPr 0.3\n")
        with open(path, "w") as f:
            f.write("mtllib %s\nusemtl gold\n" % mtl.rsplit("/", 1)[-1])
            f.write("".join("v %.7g %.7g %.7g\n" % tuple(pos[i:i + 3]) for i in range(0, len(pos), 3)))
            f.write("".join("vn %.7g %.7g %.7g\n" % tuple(nrm[i:i + 3]) for i in range(0, len(nrm), 3)))
            f.write("".join("vt %.7g %.7g\n" % (uv[i], 1 - uv[i + 1]) for i in range(0, len(uv), 2)))
            f.write("".join("f %d/%d/%d %d/%d/%d %d/%d/%d\n" % ((idx[i] + 1,) * 3 + (idx[i + 1] + 1,) * 3 + (idx[i + 2] + 1,) * 3)
                            for i in range(0, len(idx), 3)))
        return
    attrs, idx = g.mesh(pos, nrm, uv, idx)
    model = {"asset": {"version": "2.0", "generator": "make_gltf_showcase.py"},
             "buffers": [{"byteLength": 0}], "bufferViews": g.views, "accessors": g.accessors,
             "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1], "metallicFactor": 1,
                                                     "roughnessFactor": 0.3}}],
             "meshes": [{"primitives": [{"attributes": attrs, "indices": idx, "material": 0}]}],
             "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
    model["buffers"][0]["byteLength"] = len(g.bin)
    write(path, model, g)


def showcase(path):
    g = Glb()
    # A 64 x 64 checker of 8-pixel squares, two warm greys.
    tex = []
    for y in range(64):
        for x in range(64):
            tex += [200, 196, 186] if ((x // 8) + (y // 8)) % 2 == 0 else [70, 66, 62]
    image_view = g.view(png(64, 64, tex))
    # A hammered surface for the copper block: a normal map of round dents, 8 across, as data
    # (x right, y up the picture, z out; each channel 2 c / 255 - 1).
    dents = []
    for y in range(64):
        for x in range(64):
            fx, fy = (x % 8 + 0.5) / 8 - 0.5, (y % 8 + 0.5) / 8 - 0.5
            nx, ny = -1.6 * fx, 1.6 * fy
            nz = math.sqrt(max(0.0, 1 - nx * nx - ny * ny))
            dents += [int(round(255 * (c + 1) / 2)) for c in (nx, ny, nz)]
    dents_view = g.view(png(64, 64, dents))
    ball_attrs, ball_idx = g.mesh(*sphere(64, 32))
    floor_attrs, floor_idx = g.mesh([-4, 0, -4, 4, 0, -4, 4, 0, 4, -4, 0, 4], [0, 1, 0] * 4,
                                    [0, 0, 4, 0, 4, 4, 0, 4], [0, 2, 1, 0, 3, 2])
    block_attrs, block_idx = g.mesh(*box([-0.25, 0, -0.25], [0.25, 0.5, 0.25]))
    panel_attrs, panel_idx = g.mesh([-1.5, 0, -0.75, 1.5, 0, -0.75, 1.5, 0, 0.75, -1.5, 0, 0.75], [0, -1, 0] * 4,
                                    [0, 0, 1, 0, 1, 1, 0, 1], [0, 1, 2, 0, 2, 3])

    def gold(roughness):
        return {"name": "gold %.2f" % roughness,
                "pbrMetallicRoughness": {"baseColorFactor": [1.0, 0.78, 0.34, 1], "metallicFactor": 1,
                                         "roughnessFactor": roughness}}
    materials = [
        {"name": "floor", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0,
                                                   "roughnessFactor": 0.6}},
        gold(0.05), gold(0.3), gold(0.7),
        {"name": "glass", "pbrMetallicRoughness": {"roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 1.5}}},
        {"name": "copper", "pbrMetallicRoughness": {"baseColorFactor": [0.95, 0.64, 0.54, 1], "metallicFactor": 1,
                                                    "roughnessFactor": 0.2},
         "normalTexture": {"index": 1, "scale": 1}},
        {"name": "panel", "emissiveFactor": [1, 0.95, 0.85],
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 6}}},
        {"name": "blue plastic", "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.25, 0.7, 1], "metallicFactor": 0,
                                                          "roughnessFactor": 0.15}},
    ]

    def prim(attrs, idx, m):
        return {"attributes": attrs, "indices": idx, "material": m}
    meshes = [{"name": "floor", "primitives": [prim(floor_attrs, floor_idx, 0)]},
              {"name": "gold smooth", "primitives": [prim(ball_attrs, ball_idx, 1)]},
              {"name": "gold", "primitives": [prim(ball_attrs, ball_idx, 2)]},
              {"name": "gold rough", "primitives": [prim(ball_attrs, ball_idx, 3)]},
              {"name": "glass", "primitives": [prim(ball_attrs, ball_idx, 4)]},
              {"name": "copper block", "primitives": [prim(block_attrs, block_idx, 5)]},
              {"name": "panel", "primitives": [prim(panel_attrs, panel_idx, 6)]},
              {"name": "plastic", "primitives": [prim(ball_attrs, ball_idx, 7)]}]
    s = 0.45
    nodes = [
        {"name": "floor", "mesh": 0},
        {"name": "balls", "translation": [0, s, -0.6], "children": [2, 3, 4]},
        {"mesh": 1, "translation": [-1.2, 0, 0], "scale": [s, s, s]},
        {"mesh": 2, "translation": [0, 0, 0], "scale": [s, s, s]},
        {"mesh": 3, "translation": [1.2, 0, 0], "scale": [s, s, s]},
        {"name": "glass", "mesh": 4, "translation": [-0.6, 0.35, 0.6], "scale": [0.35, 0.35, 0.35]},
        {"name": "block", "mesh": 5, "translation": [0.75, 0, 0.35], "rotation": [0, 0.3826834, 0, 0.9238795]},
        {"name": "panel", "mesh": 6, "translation": [0, 3.2, 0.5]},
        {"name": "plastic", "mesh": 7, "translation": [1.6, 0.25, 0.9], "scale": [0.25, 0.25, 0.25]},
        {"name": "camera", "camera": 0, "translation": [0, 1.55, 4.2], "rotation": [-0.1305262, 0, 0, 0.9914449]},
        {"name": "lamp", "translation": [-2.5, 2.5, 2.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "plastic 2", "mesh": 7, "translation": [-1.7, 0.25, 0.8], "scale": [0.25, 0.25, 0.25]},
    ]
    model = {
        "asset": {"version": "2.0", "generator": "make_gltf_showcase.py"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_transmission",
                           "KHR_materials_ior"],
        "buffers": [{"byteLength": 0}], "bufferViews": g.views, "accessors": g.accessors,
        "images": [{"bufferView": image_view, "mimeType": "image/png"},
                   {"bufferView": dents_view, "mimeType": "image/png"}],
        "samplers": [{"magFilter": 9728, "wrapS": 10497, "wrapT": 10497}],
        "textures": [{"source": 0, "sampler": 0}, {"source": 1}],
        "materials": materials, "meshes": meshes, "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.62, "znear": 0.05, "aspectRatio": 1.5}}],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0.85, 0.7], "intensity": 6}]}},
        "scenes": [{"nodes": [i for i in range(len(nodes)) if i not in (2, 3, 4)]}], "scene": 0,
    }
    model["buffers"][0]["byteLength"] = len(g.bin)
    write(path, model, g)


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "tests/data/models/showcase.glb"
    if "--sphere-triangles" in sys.argv:
        big(out, int(sys.argv[sys.argv.index("--sphere-triangles") + 1]))
    else:
        showcase(out)
