#!/usr/bin/python3
"""Checks stages 6 and 7's converged references against a second, independent method, 8 x 8 pixels at a time.

    tools/check_references.py [--build build/release]

Each reference of assets/references/ that stage 6's tests and charts read is the mean of two halves
rendered on different seeds, and each has a second render of the same scene by another of the
project's methods, also in two halves (assets/references/README.md gives every command). For each
block of 8 x 8 pixels the two means must agree within their own errors:

    z = |m_ref - m_other| / sqrt(s_ref^2 + s_other^2) <= 4.5,

where m is a block's mean grey value and s its standard error, estimated from the halves: the mean
of two independent halves a and b has, per pixel, the variance (a - b)^2 / 4 (one degree of freedom
each, 64 in a block). Under the normal approximation a block fails by chance with probability 7e-6,
so all the blocks of the four scenes together (about 760) pass with probability 0.995.

Only the pixels that the other method renders completely take part: light tracing (and BDPT, in
the scene whose reference is SPPM's) cannot see a mirror or glass surface straight from the camera.
Those pixels are found with stage 4, the scene lit by a constant sky besides its own lights: a pixel
any of whose 64 samples sees such a surface comes out different at --max-depth 0 (black there) and
16 (the lit world through it); a block is compared when at least 16 of its pixels are left. The check also makes sure each stored reference is exactly the mean of its halves.
Exit code 0 when every block agrees, 1 otherwise; it prints each scene's worst block.
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

import pfm

ROOT = pathlib.Path(__file__).resolve().parent.parent
REFERENCES = ROOT / "assets" / "references"
BLOCK = 8
MIN_PIXELS = 16
MIN_BLOCKS = 48  # of 192: the pane of caustic-through-glass.json hides two thirds of its image
MAX_Z = 4.5

# scene, reference, its two halves, the independent method's two halves
SCENES = [
    ("caustic.json", "caustic-128x96.pfm", "bdpt", "lt"),
    ("light-through-gap.json", "light-through-gap-128x96.pfm", "bdpt", "lt"),
    ("caustic-through-glass.json", "caustic-through-glass-128x96.pfm", "sppm", "bdpt"),
    ("door-ajar.json", "door-ajar-128x96.pfm", "bdpt", "lt"),
]


def halves(reference, method):
    stem = reference.removesuffix(".pfm")
    return [REFERENCES / f"{stem}.{method}-{half}.pfm" for half in ("a", "b")]


def seen_without_delta(build, scene, width, height, scratch):
    """True where no sample of the pixel sees a mirror or glass surface from the camera."""
    # Lit by a constant sky as well, so that whatever a mirror or glass shows at depth 16 is lit
    # (behind the pane of caustic-through-glass.json lies floor that no light reaches directly).
    description = json.loads((ROOT / "assets" / "scenes" / scene).read_text())
    description.pop("background", None)
    description["environment"] = {"radiance": [1, 1, 1]}
    lit = pathlib.Path(scratch) / scene
    lit.write_text(json.dumps(description))
    images = []
    for depth in (0, 16):
        out = pathlib.Path(scratch) / f"depth{depth}.pfm"
        subprocess.run([str(build / "bin" / "stage4"), "--scene", str(lit),
                        "--width", str(width), "--height", str(height), "--spp", "64", "--filter", "box",
                        "--max-depth", str(depth), "--out", str(out)], check=True, capture_output=True)
        images.append(pfm.read_pfm(out))
    return (images[0] == images[1]).all(axis=2)


def block_means(a, b, mask):
    """Per block: the mean grey value of the halves' mean over the masked pixels, its standard error,
    and how many pixels took part."""
    grey_a, grey_b = a.mean(axis=2), b.mean(axis=2)
    height, width = mask.shape
    rows, cols = height // BLOCK, width // BLOCK
    means, errors, counts = (np.zeros((rows, cols)) for _ in range(3))
    for r in range(rows):
        for c in range(cols):
            window = (slice(r * BLOCK, (r + 1) * BLOCK), slice(c * BLOCK, (c + 1) * BLOCK))
            m = mask[window]
            n = int(m.sum())
            counts[r, c] = n
            if n == 0:
                continue
            pa, pb = grey_a[window][m], grey_b[window][m]
            means[r, c] = ((pa + pb) / 2).mean()
            errors[r, c] = np.sqrt((((pa - pb) / 2) ** 2).sum()) / n
    return means, errors, counts


def check_scene(build, scene, reference, method, other, scratch):
    problems = []
    mean = pfm.read_pfm(REFERENCES / reference)
    ref_a, ref_b = (pfm.read_pfm(p) for p in halves(reference, method))
    other_a, other_b = (pfm.read_pfm(p) for p in halves(reference, other))
    if not np.allclose(mean, (ref_a + ref_b) / 2, rtol=1e-6, atol=1e-7):
        problems.append(f"{reference} is not the mean of its halves")
    mask = seen_without_delta(build, scene, mean.shape[1], mean.shape[0], scratch)
    m_ref, s_ref, counts = block_means(ref_a, ref_b, mask)
    m_other, s_other, _ = block_means(other_a, other_b, mask)
    compared = counts >= MIN_PIXELS
    error = np.sqrt(s_ref ** 2 + s_other ** 2)
    z = np.where(compared & (error > 0), np.abs(m_ref - m_other) / np.maximum(error, 1e-30), 0.0)
    z = np.where(compared & (error == 0) & (m_ref != m_other), np.inf, z)
    worst = np.unravel_index(np.argmax(z), z.shape)
    print(f"check_references: {reference} ({method}) against {other}: {int(compared.sum())} of {z.size} blocks "
          f"compared; worst block x {worst[1] * BLOCK}, y {worst[0] * BLOCK}: {m_ref[worst]:.4g} against "
          f"{m_other[worst]:.4g}, z = {z[worst]:.2f}")
    for r, c in zip(*np.nonzero(z > MAX_Z)):
        problems.append(f"{reference}: block x {c * BLOCK}, y {r * BLOCK}: {m_ref[r, c]:.4g} ({method}) against "
                        f"{m_other[r, c]:.4g} ({other}), z = {z[r, c]:.2f}")
    if compared.sum() < MIN_BLOCKS:
        problems.append(f"{reference}: only {int(compared.sum())} of {z.size} blocks could be compared")
    return problems


def main():
    parser = argparse.ArgumentParser(description="Check stage 6's references against an independent method.")
    parser.add_argument("--build", default=str(ROOT / "build" / "release"), help="a build with bin/stage4")
    args = parser.parse_args()
    problems = []
    with tempfile.TemporaryDirectory(prefix="check-references-") as scratch:
        for scene, reference, method, other in SCENES:
            problems += check_scene(pathlib.Path(args.build), scene, reference, method, other, scratch)
    for problem in problems:
        print(f"check_references: {problem}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
