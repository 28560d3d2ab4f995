#!/usr/bin/env python3
"""Writes tests/data/whitted/sky.hdr, the lat-long environment map of environment.xml: a Radiance
HDR file (flat RGBE pixels), 128 x 64, row 0 the top (+y). A sky from blue overhead to pale at the
horizon, a broad warm sun 25 degrees up, a dark ground below. Run from the repository's root:

    python3 tests/data/whitted/make_sky.py
"""
import math

W, H = 128, 64
sun = (math.cos(math.radians(25)) * math.sin(math.radians(-40)), math.sin(math.radians(25)),
       -math.cos(math.radians(25)) * math.cos(math.radians(-40)))


def direction(x, y):
    # The inverse of u = (1 + atan2(dx, -dz) / pi) / 2, v = acos(dy) / pi at the texel's centre.
    u, v = (x + 0.5) / W, (y + 0.5) / H
    phi, theta = (2 * u - 1) * math.pi, v * math.pi
    return (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))


def radiance(d):
    if d[1] < 0:  # the ground
        return (40.0, 34.0, 28.0)
    t = d[1]
    sky = (120 + 60 * (1 - t), 150 + 70 * (1 - t), 255.0)
    c = sum(a * b for a, b in zip(d, sun))
    glow = 900.0 if c > math.cos(math.radians(12)) else 0.0
    return (sky[0] + glow, sky[1] + glow * 0.9, sky[2] + glow * 0.75)


def rgbe(rgb):
    m = max(rgb)
    if m < 1e-32:
        return bytes(4)
    e = math.frexp(m)[1]
    scale = 256.0 / 2.0 ** e
    return bytes([int(c * scale) for c in rgb] + [e + 128])


with open("tests/data/whitted/sky.hdr", "wb") as f:
    f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (H, W))
    for y in range(H):
        for x in range(W):
            f.write(rgbe(radiance(direction(x, y))))
