"""Images for the grader: PFM in and out (the renders, through tools/pfm.py), PNG out (the
reports), and the pictures the reports show (display transform, difference heat map). numpy arrays
of shape (height, width, 3), row 0 at the top."""
import pathlib
import struct
import sys
import zlib

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent))
from pfm import decode_pfm, read_pfm, write_pfm  # noqa: E402,F401  (the grader's names for them)


def to_display(image):
    """Linear radiance to 8-bit sRGB (the stage programs' own PNG transform: clamp, then the sRGB curve)."""
    x = np.clip(np.nan_to_num(image, nan=0.0, posinf=1.0, neginf=0.0), 0.0, 1.0)
    srgb = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return np.round(srgb * 255).astype(np.uint8)


def heat_map(values, top):
    """Non-negative values as colours from black (0) through red to yellow and white (>= top)."""
    x = np.clip(np.nan_to_num(values, nan=top) / top, 0.0, 1.0)
    rgb = np.stack([np.clip(3 * x, 0, 1), np.clip(3 * x - 1, 0, 1), np.clip(3 * x - 2, 0, 1)], axis=-1)
    return np.round(rgb * 255).astype(np.uint8)


def png_bytes(rgb8, scale=1):
    """An 8-bit RGB image as PNG bytes (zlib from the standard library), each pixel `scale` times."""
    if scale > 1:
        rgb8 = np.repeat(np.repeat(rgb8, scale, axis=0), scale, axis=1)
    height, width, _ = rgb8.shape
    rows = b"".join(b"\0" + rgb8[y].tobytes() for y in range(height))

    def chunk(kind, payload):
        return struct.pack(">I", len(payload)) + kind + payload + struct.pack(">I", zlib.crc32(kind + payload))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")
