#!/usr/bin/env python3
"""Writes valley.png: the 16-bit greyscale heightmap of examples/valley.geojson.

A valley floor rising to hills east and west, with a meandering river whose pixels are 0
(water, as Exacity reads it). Pure standard library, so it runs anywhere:
    python3 examples/make_valley_heightmap.py examples/valley.png
"""
import math
import struct
import sys
import zlib

W, H = 200, 150          # pixels; the sketch stretches them over 2000 m x 1500 m
METRES_PER_PIXEL = 10.0


def river_x(y):
    return 1000.0 + 180.0 * math.sin(y / 260.0)


def value(col, row):
    x = (col + 0.5) * METRES_PER_PIXEL
    y = (H - row - 0.5) * METRES_PER_PIXEL  # row 0 is the north edge
    d = abs(x - river_x(y))
    if d < 45.0:
        return 0
    hills = 0.25 + 0.75 * min(1.0, (d - 45.0) / 900.0) ** 1.5
    ripple = 0.03 * math.sin(x / 97.0) * math.cos(y / 131.0)
    return max(1, min(65535, int(65535 * (hills + ripple))))


def png(path):
    raw = bytearray()
    for row in range(H):
        raw.append(0)  # filter: none
        for col in range(W):
            raw += struct.pack(">H", value(col, row))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", W, H, 16, 0, 0, 0, 0)  # 16-bit greyscale
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(bytes(raw), 9))
                + chunk(b"IEND", b""))


if __name__ == "__main__":
    png(sys.argv[1] if len(sys.argv) > 1 else "valley.png")
