#!/usr/bin/env python3
"""Writes the texture images of textures.xml (tests/data/whitted/textures/*.png), 8-bit RGB PNGs
made from formulas, so the scene needs no course files. Run from the repository's root:

    python3 tests/data/whitted/make_textures.py

tiles.png      64 x 64: 8 x 8 coloured tiles with dark grout, a diffuse map (replace_kd)
bumps.png      64 x 64: a grey height field of round domes, a bump map (bump_normal)
normals.png    64 x 64: the normal map of the same domes (replace_normal): n -> (n + 1) / 2 * 255
backdrop.png   32 x 16: a dusk gradient, the film's background (replace_background)
"""
import math
import os
import struct
import zlib


def write_png(path, w, h, pixel):
    rows = b"".join(b"\x00" + bytes(c for x in range(w) for c in pixel(x, y)) for y in range(h))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def clamp8(x):
    return max(0, min(255, int(round(x))))


def tile(x, y):
    tx, ty = x // 8, y // 8
    if x % 8 == 0 or y % 8 == 0:
        return (40, 36, 32)
    hue = (tx * 3 + ty * 5) % 6
    palette = [(200, 80, 60), (230, 170, 60), (90, 160, 90), (70, 120, 200), (160, 90, 180), (220, 220, 210)]
    return palette[hue]


def dome(x, y):
    # Height in [0, 1] and its gradient: one dome per 16 x 16 cell.
    cx, cy = (x % 16) - 7.5, (y % 16) - 7.5
    r2 = (cx * cx + cy * cy) / 49.0
    if r2 >= 1:
        return 0.0, 0.0, 0.0
    h = math.sqrt(1 - r2)
    return h, -cx / (49.0 * h), -cy / (49.0 * h)


def bump(x, y):
    v = clamp8(255 * dome(x, y)[0])
    return (v, v, v)


def normal(x, y):
    _, gx, gy = dome(x, y)
    s = 6.0  # steepness
    n = (-s * gx, -s * gy, 1.0)
    length = math.sqrt(sum(c * c for c in n))
    return tuple(clamp8((c / length + 1) / 2 * 255) for c in n)


def backdrop(x, y):
    t = y / 15.0
    return (clamp8(40 + 150 * t), clamp8(30 + 70 * t), clamp8(90 + 20 * t))


if __name__ == "__main__":
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "textures")
    os.makedirs(out, exist_ok=True)
    write_png(os.path.join(out, "tiles.png"), 64, 64, tile)
    write_png(os.path.join(out, "bumps.png"), 64, 64, bump)
    write_png(os.path.join(out, "normals.png"), 64, 64, normal)
    write_png(os.path.join(out, "backdrop.png"), 32, 16, backdrop)
