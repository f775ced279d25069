"""PFM images for the tools (the grader, the charts, the references): numpy arrays of shape
(height, width, 3) with row 0 at the TOP, as the renderer's images are (docs/design.md). The file
stores the bottom row first (the PFM convention), so reading and writing turn the rows over here,
and only here. Needs numpy (Debian's python3-numpy)."""
import pathlib

import numpy as np


def decode_pfm(data, path):
    """A colour PFM's bytes as an image; raises ValueError naming `path`."""
    try:
        header, size, scale, rest = data.split(b"\n", 3)
        width, height = map(int, size.split())
        scale = float(scale)
    except ValueError:
        raise ValueError(f"{path}: not a PFM file")
    if header.strip() != b"PF" or width <= 0 or height <= 0 or len(rest) != width * height * 12:
        raise ValueError(f"{path}: not a {width}x{height} colour PFM")
    pixels = np.frombuffer(rest, dtype="<f4" if scale < 0 else ">f4").reshape(height, width, 3)
    return pixels[::-1].astype(np.float64)


def read_pfm(path):
    return decode_pfm(pathlib.Path(path).read_bytes(), path)


def write_pfm(path, image):
    """Little-endian (scale -1), bottom row first."""
    height, width, _ = image.shape
    body = np.ascontiguousarray(image[::-1], dtype="<f4").tobytes()
    pathlib.Path(path).write_bytes(f"PF\n{width} {height}\n-1\n".encode() + body)
