#!/usr/bin/env python3
"""Writes algorithms/textures/test-card.png: the image the mapping entries wrap onto a
plane, a cylinder and a sphere. 360x180 texels (not a power of two, on purpose: the
mip-map resamples it), a 12x6 grid of cells whose hue follows u and lightness follows
v, dark grid lines, and an asymmetric "F" glyph near (u, v) = (0.25, 0.5) so that
mirroring or rotation is visible. Pure Python (zlib), so it runs anywhere."""
import colorsys
import struct
import sys
import zlib
from pathlib import Path

W, H, COLS, ROWS = 360, 180, 12, 6


def texel(x, y):
    cell_w, cell_h = W // COLS, H // ROWS
    if x % cell_w in (0, 1) or y % cell_h in (0, 1):
        return (25, 25, 30)
    # The glyph: an F made of three bars, left of the image's first quarter.
    gx, gy = x - 70, y - 55
    if (0 <= gx < 12 and 0 <= gy < 70) or (0 <= gx < 45 and 0 <= gy < 12) or (
        0 <= gx < 32 and 30 <= gy < 42
    ):
        return (250, 250, 250)
    hue = (x // cell_w) / COLS
    light = 0.30 + 0.45 * (1 - (y // cell_h) / (ROWS - 1))
    r, g, b = colorsys.hls_to_rgb(hue, light, 0.75)
    return (round(r * 255), round(g * 255), round(b * 255))


def png(width, height, rows):
    raw = b"".join(b"\x00" + bytes(c for p in row for c in p) for row in rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(raw, 9))
        + chunk(b"IEND", b"")
    )


if __name__ == "__main__":
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "algorithms/textures/test-card.png")
    out.write_bytes(png(W, H, [[texel(x, y) for x in range(W)] for y in range(H)]))
