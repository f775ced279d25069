#!/usr/bin/env python3
"""The costs per unit of work that stage 7's budget choice weighs (stages/07-vcm-mlt/vcm_budget.cpp),
measured again: on each of the chart's five scenes (128 x 96 pixels, one thread), the first
iteration's counts (stage7 prints them), then the time per iteration of every budget (`--budget
WORD`, 16 iterations less 1, so that loading the scene cancels), and a least-squares fit of the
counts to the times, each time weighed by its inverse (relative error). Prints the fitted costs in
camera vertices, each budget's predicted time against its measured one, the same for the costs in
use (read from vcm_budget.cpp, one common scale fitted), and the path tracer's time per camera
vertex and light point.

    benchmarks/fit_vcm_costs.py [BUILD]        (default build/release; about two minutes)

Light vertices and their links to the camera come in equal numbers, so they are fitted as one cost
(the constants split it evenly); camera vertices and light points, and light vertices and photons,
come in nearly fixed proportions, so the single costs move between fits while the times they
predict do not: compare the predictions. Run it on an idle machine: the times are wall-clock.
"""
import pathlib
import re
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENES = ["cornell-box", "caustic", "caustic-through-glass", "light-through-gap", "door-ajar"]
WORDS = ["1", "1m", "1c", "1cm", "8", "8m", "8c", "8cm"]
WORK = re.compile(r"work: (\d+) camera vertices, (\d+) light points, (\d+) light subpaths, "
                  r"(\d+) light vertices, (\d+) camera links, (\d+) connections; "
                  r"with connections (\d+) photons and (\d+) merges, without (\d+) and (\d+)")
NAMES = ["camera vertex", "light point", "light subpath", "light vertex + link", "connection", "merge",
         "photon in the grid"]
CONSTANTS = ["CameraVertex", "LightPoint", "LightSubpath", "LightVertex", "CameraLink", "Connection", "Merge", "Photon"]


OUT = pathlib.Path(tempfile.mkdtemp(prefix="fit_vcm_costs.")) / "image.pfm"


def run(program, scene, *flags):
    command = [str(program), "--scene", str(ROOT / "assets" / "scenes" / f"{scene}.json"), "--width", "128",
               "--height", "96", "--threads", "1", "--out", str(OUT), *flags]
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True)
    seconds = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"fit_vcm_costs: {' '.join(command)}: {done.stderr.strip()}")
    return done.stdout, seconds


def per_iteration(program, scene, word):
    sixteen = run(program, scene, "--budget", word, "--spp", "16")[1]
    return (sixteen - run(program, scene, "--budget", word, "--spp", "1")[1]) / 15


def solve(a, b):
    """Least squares by the normal equations (7 unknowns), Gaussian elimination with pivoting."""
    n = len(a[0])
    m = [[sum(r[i] * r[j] for r in a) for j in range(n)] + [sum(r[i] * y for r, y in zip(a, b))] for i in range(n)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(n):
            if r != c and m[c][c] != 0:
                f = m[r][c] / m[c][c]
                m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    return [m[i][n] / m[i][i] for i in range(n)]


def main():
    build = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build" / "release")
    program = build / "bin" / "stage7"
    if not program.exists():
        sys.exit(f"fit_vcm_costs: no {program}: build the release preset first")
    rows, path_tracer = [], []
    for scene in SCENES:
        text, _ = run(program, scene, "--spp", "2")
        found = WORK.search(text)
        if not found:
            sys.exit(f"fit_vcm_costs: {scene}: stage7 printed no counts")
        cam, nee, subpaths, light, links, conn, photons_c, merges_c, photons, merges = map(float, found.groups())
        for word in WORDS:
            n, c, m = int(word[0]), "c" in word, "m" in word
            # A budget with connections merges only where they cannot reach, one without at more vertices.
            x = [cam, nee, n * subpaths, n * (light + links), conn if c else 0.0,
                 n * (merges_c if c else merges) if m else 0.0, n * (photons_c if c else photons) if m else 0.0]
            rows.append((scene, word, x, per_iteration(program, scene, word)))
        path_tracer.append((scene, per_iteration(program, scene, "pt") / (cam + nee)))
    a = [[v / t for v in x] for _, _, x, t in rows]
    k = solve(a, [1.0] * len(rows))
    source = (ROOT / "stages" / "07-vcm-mlt" / "vcm_budget.cpp").read_text()
    used = {m.group(1): float(m.group(2)) for m in re.finditer(r"constexpr double kCost(\w+) = ([\d.]+);", source)}
    u = [used[CONSTANTS[0]], used[CONSTANTS[1]], used[CONSTANTS[2]], used[CONSTANTS[3]] + used[CONSTANTS[4]],
         used[CONSTANTS[5]], used[CONSTANTS[6]], used[CONSTANTS[7]]]
    predicted = [sum(c * v for c, v in zip(u, x)) for _, _, x, _ in rows]
    # The one scale that fits the constants in use best (relative error): seconds per camera vertex.
    scale = sum(p / t for p, (_, _, _, t) in zip(predicted, rows)) / sum((p / t) ** 2 for p, (_, _, _, t) in
                                                                           zip(predicted, rows))
    print("cost per unit, in camera vertices: fitted now, and in use (vcm_budget.cpp)")
    for name, c, c_used in zip(NAMES, k, u):
        print(f"  {name:22} {c / k[0]:6.3f} {c_used:6.3f}")
    print("predicted / measured time per iteration: fitted now, and by the costs in use")
    for (scene, word, x, t), p in zip(rows, predicted):
        print(f"  {scene:24} {word:4} {sum(c * v for c, v in zip(k, x)) / t:.2f} {scale * p / t:.2f}  ({t * 1000:.1f} ms)")
    print("stage 5's path tracer, per camera vertex and light point, in camera vertices: fitted now, in use")
    for scene, seconds in path_tracer:
        print(f"  {scene:24} {seconds / k[0]:.2f} {seconds / scale:.2f}")
    OUT.unlink(missing_ok=True)
    OUT.parent.rmdir()


if __name__ == "__main__":
    main()
