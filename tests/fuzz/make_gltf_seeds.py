#!/usr/bin/env python3
"""Writes the glTF harness's seeds, tests/fuzz/corpus/gltf/*: small .gltf files with their buffers
as data URIs and one .glb, each under the harness's 4096 bytes, covering what io/gltf_model.h
reads (accessor types, strides, strips and fans, node matrices and TRS, instances, materials and
their extensions, a data-URI PNG, a picture beside the file, cameras, lights).

    python3 tests/fuzz/make_gltf_seeds.py tests/fuzz/corpus/gltf
"""
import base64
import json
import struct
import sys
import zlib
from pathlib import Path


def png(width, height, rgb):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    rows = b"".join(b"\0" + bytes(rgb[y * width * 3:(y + 1) * width * 3]) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))


def data_uri(kind, data):
    return "data:%s;base64,%s" % (kind, base64.b64encode(data).decode())


class Builder:
    """One buffer of accessors, added in order."""

    def __init__(self):
        self.bin = b""
        self.views, self.accessors = [], []

    def add(self, fmt, values, component, kind, count, stride=0, normalized=False):
        while len(self.bin) % 4:
            self.bin += b"\0"
        data = struct.pack("<" + fmt * len(values), *values)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            view["byteStride"] = stride
        self.bin += data
        self.views.append(view)
        acc = {"bufferView": len(self.views) - 1, "componentType": component, "count": count, "type": kind}
        if normalized:
            acc["normalized"] = True
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def gltf(self, rest, embed=True):
        g = {"asset": {"version": "2.0"}, "bufferViews": self.views, "accessors": self.accessors,
             "buffers": [{"byteLength": len(self.bin)}]}
        if embed:
            g["buffers"][0]["uri"] = data_uri("application/octet-stream", self.bin)
        g.update(rest)
        return g


def square(b, uv_component=5126):
    pos = b.add("f", [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0], 5126, "VEC3", 4)
    idx = b.add("H", [0, 1, 2, 0, 2, 3], 5123, "SCALAR", 6)
    nrm = b.add("f", [0, 0, 1] * 4, 5126, "VEC3", 4)
    if uv_component == 5126:
        uv = b.add("f", [0, 1, 1, 1, 1, 0, 0, 0], 5126, "VEC2", 4)
    else:
        uv = b.add("B", [0, 255, 255, 255, 255, 0, 0, 0], 5121, "VEC2", 4, normalized=True)
    return {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}, idx


def main(out):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    seeds = {}

    b = Builder()
    attrs, idx = square(b)
    seeds["square.gltf"] = b.gltf({
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.3, 0.2, 1], "metallicFactor": 0.2,
                                                "roughnessFactor": 0.5}}],
        "meshes": [{"primitives": [{"attributes": attrs, "indices": idx, "material": 0}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "aspectRatio": 1.5}}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 3]},
                  {"translation": [0, 2, 2], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "scenes": [{"nodes": [0, 1, 2]}], "scene": 0,
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"type": "point", "color": [1, 0.9, 0.8], "intensity": 5},
            {"type": "spot", "intensity": 2, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
            {"type": "directional", "intensity": 1}]}}})

    b = Builder()
    attrs, idx = square(b, uv_component=5121)
    picture = png(2, 2, [255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255])
    seeds["textured.gltf"] = b.gltf({
        "materials": [
            {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1},
                                      "metallicFactor": 0.5},
             "normalTexture": {"index": 0, "scale": 1}, "occlusionTexture": {"index": 0}},
            {"emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 1}, "doubleSided": True,
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 3}}}],
        "textures": [{"source": 0, "sampler": 0}, {"source": 0, "sampler": 1}],
        "samplers": [{"magFilter": 9728, "wrapS": 33648, "wrapT": 33071}, {"wrapS": 10497}],
        "images": [{"uri": data_uri("image/png", picture)}],
        "meshes": [{"primitives": [{"attributes": attrs, "indices": idx, "material": 0},
                                   {"attributes": attrs, "indices": idx, "material": 1}]}],
        "nodes": [{"mesh": 0, "translation": [0, 0, -1]}], "scenes": [{"nodes": [0]}]})

    # TANGENT (a normal map's frame) and COLOR_0 (RGBA as normalised shorts), placed twice
    # (instances).
    b = Builder()
    attrs, idx = square(b)
    attrs["TANGENT"] = b.add("f", [0.7071, 0.7071, 0, 1] * 4, 5126, "VEC4", 4)
    attrs["COLOR_0"] = b.add("H", [65535, 0, 0, 65535, 0, 65535, 0, 65535, 0, 0, 65535, 32768, 65535, 65535, 65535, 0],
                             5123, "VEC4", 4, normalized=True)
    seeds["attributes.gltf"] = b.gltf({
        "materials": [{"normalTexture": {"index": 0}, "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 1, 1]}}],
        "textures": [{"source": 0}],
        "images": [{"uri": data_uri("image/png", png(1, 1, [218, 128, 218]))}],
        "meshes": [{"primitives": [{"attributes": attrs, "indices": idx, "material": 0}]}],
        "nodes": [{"mesh": 0, "translation": [-1.5, 0, 0]}, {"mesh": 0, "rotation": [0, 0, 0.7071068, 0.7071068]}],
        "scenes": [{"nodes": [0, 1]}]})

    b = Builder()
    pos = b.add("f", [0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0, 1, 2, 0], 5126, "VEC3", 6)
    fan = b.add("B", [0, 1, 3, 2], 5121, "SCALAR", 4)
    seeds["hierarchy.gltf"] = b.gltf({
        "materials": [{"extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                      "KHR_materials_ior": {"ior": 1.33}},
                       "pbrMetallicRoughness": {"roughnessFactor": 0.1}}, {"alphaMode": "MASK"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "mode": 5, "material": 0},
                                   {"attributes": {"POSITION": pos}, "indices": fan, "mode": 6, "material": 1},
                                   {"attributes": {"POSITION": pos}, "mode": 1}]}],
        "nodes": [{"children": [1, 2], "rotation": [0, 0.3826834, 0, 0.9238795]},
                  {"mesh": 0, "scale": [1, 2, 1]},
                  {"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 2, 0, 0, 1], "children": [3]},
                  {"mesh": 0, "translation": [0, 0, 1]}],
        "scenes": [{"nodes": [0]}, {"nodes": [3]}], "scene": 0,
        "animations": [], "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_ior", "KHR_texture_transform"]})

    b = Builder()
    # Interleaved positions and normals, one stride.
    vertices = []
    for x, y in [(-1, -1), (1, -1), (1, 1), (-1, 1)]:
        vertices += [x, y, 0, 0, 0, 1]
    data = struct.pack("<24f", *vertices)
    b.bin = data
    b.views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(data), "byteStride": 24}]
    b.accessors = [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                   {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 4, "type": "VEC3"}]
    idx = b.add("I", [0, 1, 2, 2, 3, 0], 5125, "SCALAR", 6)
    seeds["interleaved.gltf"] = b.gltf({
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": idx}]}],
        "nodes": [{"mesh": 0, "translation": [-1.5, 0, 0]}, {"mesh": 0, "translation": [1.5, 0, 0]}]})

    b = Builder()
    attrs, idx = square(b)
    seeds["beside.gltf"] = b.gltf({
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}], "images": [{"uri": "still_life_tiles.png"}],
        "meshes": [{"primitives": [{"attributes": attrs, "indices": idx, "material": 0}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})

    for name, g in seeds.items():
        text = json.dumps(g, separators=(",", ":")).encode()
        assert len(text) <= 4096, (name, len(text))
        (out / name).write_bytes(text)

    # One GLB: the square with its buffer in the BIN chunk.
    b = Builder()
    attrs, idx = square(b)
    g = b.gltf({"materials": [{"pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.2}}],
                "meshes": [{"primitives": [{"attributes": attrs, "indices": idx, "material": 0}]}],
                "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]}, embed=False)
    js = json.dumps(g, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    bin_ = b.bin + b"\0" * (-len(b.bin) % 4)
    total = 12 + 8 + len(js) + 8 + len(bin_)
    glb = (b"glTF" + struct.pack("<II", 2, total) + struct.pack("<I", len(js)) + b"JSON" + js +
           struct.pack("<I", len(bin_)) + b"BIN\0" + bin_)
    assert len(glb) <= 4096
    (out / "square.glb").write_bytes(glb)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "tests/fuzz/corpus/gltf")
