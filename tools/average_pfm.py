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

from pfm import read_pfm, write_pfm


def main(out, inputs):
    images = [read_pfm(p) for p in inputs]
    if any(i.shape != images[0].shape for i in images):
        sys.exit("average_pfm: the images differ in size")
    if len(images) == 2:
        rmse = float(np.sqrt(np.mean((images[0] - images[1]) ** 2)))
        print(f"RMSE between the two: {rmse:.6f}; each one's RMSE ~ {rmse / np.sqrt(2):.6f}; "
              f"the mean's ~ {rmse / 2:.6f}")
    write_pfm(out, sum(images) / len(images))
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
