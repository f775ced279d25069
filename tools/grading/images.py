"""Images for the grader: PFM in and out (the renders), PNG out (the reports), and the pictures the
reports show (display transform, difference heat map). numpy arrays of shape (height, width, 3),
row 0 at the top."""
import pathlib
import struct
import zlib

import numpy as np


def read_pfm(path):
    """A colour PFM (header "PF"), as the stage programs write it; raises ValueError naming the file."""
    return decode_pfm(pathlib.Path(path).read_bytes(), path)


def decode_pfm(data, path):
    """The same from the file's bytes; `path` names it in messages."""
    try:
        header, size, scale, rest = data.split(b"\n", 3)
        width, height = map(int, size.split())
        scale = float(scale)
    except ValueError:
        raise ValueError(f"{path}: not a PFM file")
    if header.strip() != b"PF" or len(rest) != width * height * 12:
        raise ValueError(f"{path}: not a {width}x{height} colour PFM")
    pixels = np.frombuffer(rest, dtype="<f4" if scale < 0 else ">f4").reshape(height, width, 3)
    return pixels[::-1].astype(np.float64)  # PFM stores the bottom row first


def write_pfm(path, image):
    height, width, _ = image.shape
    body = np.ascontiguousarray(image[::-1], dtype="<f4").tobytes()
    pathlib.Path(path).write_bytes(f"PF\n{width} {height}\n-1\n".encode() + body)


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
