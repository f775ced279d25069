#!/usr/bin/python3
"""Averages PFM images of the same scene (renders with different seeds) into one, and says how
far apart they are: for two renders of equal sample counts, each has an RMSE against the truth of
RMSE(a - b) / sqrt(2), and their mean RMSE(a - b) / 2 (independent errors add in quadrature).

    tools/average_pfm.py OUT.pfm IN1.pfm IN2.pfm [...]

Used to make the converged references in assets/references/ (see the README there). Needs
Debian's numpy (python3-numpy, which python3-matplotlib brings).
"""
import sys

import numpy as np


def read_pfm(path):
    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            sys.exit(f"{path}: not a colour PFM file")
        width, height = (int(v) for v in f.readline().split())
        scale = float(f.readline())
        data = np.frombuffer(f.read(), dtype="<f4" if scale < 0 else ">f4")
    if data.size != width * height * 3:
        sys.exit(f"{path}: expected {width}x{height} pixels, found {data.size // 3}")
    return data.reshape(height, width, 3).astype(np.float64)


def write_pfm(path, image):
    height, width, _ = image.shape
    with open(path, "wb") as f:
        f.write(f"PF\n{width} {height}\n-1\n".encode())
        f.write(image.astype("<f4").tobytes())


def main(out, inputs):
    images = [read_pfm(p) for p in inputs]
    if any(i.shape != images[0].shape for i in images):
        sys.exit("average_pfm: the images differ in size")
    if len(images) == 2:
        rmse = float(np.sqrt(np.mean((images[0] - images[1]) ** 2)))
        print(f"RMSE between the two: {rmse:.6f}; each one's RMSE ~ {rmse / np.sqrt(2):.6f}; "
              f"the mean's ~ {rmse / 2:.6f}")
    write_pfm(out, sum(images) / len(images))  # rows stay in file order (bottom first)
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
