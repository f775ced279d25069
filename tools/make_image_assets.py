#!/usr/bin/env python3
"""Writes the two images the scenes use, so that no asset is downloaded:

  assets/textures/uv-grid.png      128 x 128 sRGB: an 8 x 8 grid whose red grows with u and green
                                   with v (texture coordinates: u right, v up), light and dark cells
                                   alternating, and a white cell in the top-left corner (u ~ 0, v ~ 1)
                                   that shows at a glance which way a mapping runs.
  assets/environments/sky.hdr      256 x 128 Radiance RGBE, latitude-longitude (row 0 straight up,
                                   column 0 along +x, columns growing towards +z): a blue sky that
                                   pales towards the horizon, a dim ground, and a sun of angular
                                   radius 3 degrees, 30 degrees above the horizon at phi = 60 degrees.

Usage: tools/make_image_assets.py   (from the repository root; deterministic, byte for byte)
"""
import math
import struct
import zlib

GRID = 128
CELLS = 8


def srgb_encode(v):
    v = min(max(v, 0.0), 1.0)
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055


def write_png(path, width, height, rows):
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(row) for row in rows)
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)  # 8-bit RGB
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def uv_grid():
    rows = []
    cell = GRID // CELLS
    for y in range(GRID):
        row = []
        for x in range(GRID):
            i, j = x // cell, y // cell          # j = 0 is the top row of cells
            u, v = (i + 0.5) / CELLS, 1.0 - (j + 0.5) / CELLS
            if i == 0 and j == 0:
                linear = (1.0, 1.0, 1.0)
            else:
                light = 1.0 if (i + j) % 2 == 0 else 0.35
                linear = (light * (0.1 + 0.8 * u), light * (0.1 + 0.8 * v), light * 0.15)
            row += [round(255 * srgb_encode(c)) for c in linear]
        rows.append(row)
    write_png("assets/textures/uv-grid.png", GRID, GRID, rows)


SUN_ELEVATION, SUN_PHI, SUN_RADIUS = math.radians(30), math.radians(60), math.radians(3)
SUN = (800.0, 720.0, 600.0)


def sky_radiance(d):
    sun = (math.cos(SUN_ELEVATION) * math.cos(SUN_PHI), math.sin(SUN_ELEVATION),
           math.cos(SUN_ELEVATION) * math.sin(SUN_PHI))
    if sum(a * b for a, b in zip(d, sun)) >= math.cos(SUN_RADIUS):
        return SUN
    if d[1] < 0.0:
        return (0.12, 0.11, 0.10)
    pale = (1.0 - d[1]) ** 3
    zenith, horizon = (0.25, 0.45, 1.0), (0.9, 0.95, 1.0)
    return tuple(z + (h - z) * pale for z, h in zip(zenith, horizon))


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return bytes(4)
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes([int(c[0] * scale), int(c[1] * scale), int(c[2] * scale), exponent + 128])


def sky():
    width, height, n = 256, 128, 4   # n x n samples per texel: the sun's rim antialiased
    out = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width))
    for y in range(height):
        pixels = []
        for x in range(width):
            total = [0.0, 0.0, 0.0]
            for sy in range(n):
                for sx in range(n):
                    theta = math.pi * (y + (sy + 0.5) / n) / height
                    phi = 2 * math.pi * (x + (sx + 0.5) / n) / width
                    d = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
                    total = [t + c for t, c in zip(total, sky_radiance(d))]
            pixels.append(rgbe([t / (n * n) for t in total]))
        # The run-length scanline format: each of the four bytes of every pixel in its own
        # plane, written as literal runs of at most 128.
        out += bytes([2, 2, width >> 8, width & 255])
        for channel in range(4):
            plane = bytes(p[channel] for p in pixels)
            for start in range(0, width, 128):
                piece = plane[start:start + 128]
                out += bytes([len(piece)]) + piece
    with open("assets/environments/sky.hdr", "wb") as f:
        f.write(bytes(out))


if __name__ == "__main__":
    uv_grid()
    sky()
