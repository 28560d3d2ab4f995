#!/usr/bin/env python3
"""Writes a lat-long sky with a small sun as a PFM (BENCHMARKS.md section 35): 256 x 128, the
orientation of rtweekend/render/environment_map.h (row 0 the top, +y; -z the middle). A blue sky
of (0.25, 0.35, 0.6) above the horizon, (0.05, 0.04, 0.03) below it, and a sun 1.5 degrees in
radius, 35 degrees up, of (3000, 2800, 2500): some 4 % of the sky's light comes from 0.005 % of
its solid angle, the case light sampling of the map is for.

    python3 tests/data/make_sun_sky.py /tmp/sun.pfm
"""
import math
import struct
import sys

W, H = 256, 128
ELEVATION, AZIMUTH, RADIUS = math.radians(35), math.radians(-30), math.radians(1.5)
sun = (math.cos(ELEVATION) * math.sin(AZIMUTH), math.sin(ELEVATION), -math.cos(ELEVATION) * math.cos(AZIMUTH))


def radiance(x, y):
    u, v = (x + 0.5) / W, (y + 0.5) / H
    phi, theta = (2 * u - 1) * math.pi, v * math.pi
    d = (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))
    if sum(a * b for a, b in zip(d, sun)) > math.cos(RADIUS):
        return (3000.0, 2800.0, 2500.0)
    return (0.25, 0.35, 0.6) if d[1] >= 0 else (0.05, 0.04, 0.03)


def main(path):
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1\n" % (W, H))
        for y in range(H - 1, -1, -1):  # a PFM's rows run bottom first
            for x in range(W):
                f.write(struct.pack("<3f", *radiance(x, y)))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "sun.pfm")
