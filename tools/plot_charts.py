#!/usr/bin/python3
"""Turns the CSV files in docs/charts/ into the PNG charts beside them.

Run through tools/make-charts.sh, which first regenerates the CSV. Needs Debian's matplotlib
(python3-matplotlib), hence /usr/bin/python3 rather than whichever python3 is first on PATH.
"""
import csv
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

COLOURS = {"textbook": "#c0392b", "stable": "#2471a3"}


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def sphere_precision(charts):
    rows = read_rows(charts / "stage1-sphere-precision.csv")
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for formula in ("textbook", "stable"):
        mine = [r for r in rows if r["formula"] == formula]
        distance = [float(r["distance_over_radius"]) for r in mine]
        ns = sum(float(r["ns_per_call"]) for r in mine) / len(mine)
        label = f"{formula} ({ns:.1f} ns/call)"
        colour = COLOURS[formula]
        left.loglog(distance, [float(r["max_relative_error"]) for r in mine], "o-", color=colour, label=f"{label}, max")
        left.loglog(distance, [float(r["median_relative_error"]) for r in mine], "s--", color=colour,
                    alpha=0.6, label=f"{formula}, median")
        right.semilogx(distance, [100.0 * float(r["wrong_fraction"]) for r in mine], "o-", color=colour, label=label)
    left.axhline(2.0 ** -24, color="grey", lw=0.8, ls=":")
    left.text(1.2, 2.0 ** -24 * 1.3, "float rounding, 2^-24", color="grey", fontsize=8)
    left.set(xlabel="sphere distance / radius", ylabel="relative error in t",
             title="Accuracy of the hit distance (agreed hits)")
    right.set(xlabel="sphere distance / radius", ylabel="wrong hit/miss answers (%)",
              title="Hit/miss decisions against long double")
    for ax in (left, right):
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Stage 1: ray-sphere intersection in float, textbook quadratic vs Ray Tracing Gems ch. 7 form")
    fig.tight_layout()
    fig.savefig(charts / "stage1-sphere-precision.png", dpi=110)
    plt.close(fig)


def offset_vs_scale(charts):
    rows = read_rows(charts / "stage2-offset-vs-scale.csv")
    methods = list(dict.fromkeys(r["method"] for r in rows))
    fig, ax = plt.subplots(figsize=(8, 4.6))
    styles = {"error bound": ("o-", "#2471a3", 2.2), "integer ulp": ("s--", "#17a589", 1.6)}
    for method in methods:
        mine = [r for r in rows if r["method"] == method]
        scale = [float(r["scale"]) for r in mine]
        # Percent of the compared pixels; a zero is drawn at the bottom of the log axis.
        wrong = [100.0 * (int(r["acne"]) + int(r["leaks"])) / int(r["pixels"]) for r in mine]
        style, colour, width = styles.get(method, ("^-", None, 1.2))
        ax.plot(scale, [max(w, 0.004) for w in wrong], style, color=colour, lw=width, label=method)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(0.002, 100)
    ax.axhline(0.004, color="grey", lw=0.6, ls=":")
    ax.text(1.2e-3, 0.0026, "zero wrong pixels", color="grey", fontsize=8)
    ax.set(xlabel="scene scale s (the whole scene multiplied by s)",
           ylabel="pixels with the wrong shadow (% of 17,597)",
           title="Stage 2: shadow-ray offsets across scene scales (acne + light leaks)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(charts / "stage2-offset-vs-scale.png", dpi=110)
    plt.close(fig)


ACCEL_STYLE = {"naive": ("o-", "#7f8c8d"), "median": ("s-", "#c0392b"), "middle": ("^-", "#d68910"),
               "sah": ("D-", "#2471a3"), "embree": ("x--", "#17a589")}


def accel_time_per_ray(charts):
    rows = [r for r in read_rows(charts / "stage3-accel.csv") if r["mesh"] != "bunny"]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), sharey=True)
    for ax, kind in zip(axes, ("incoherent", "coherent")):
        for accel, (style, colour) in ACCEL_STYLE.items():
            mine = [r for r in rows if r["accel"] == accel]
            if not mine:
                continue
            ax.loglog([int(r["triangles"]) for r in mine], [float(r[f"{kind}_ns_per_ray"]) for r in mine], style,
                      color=colour, label=accel)
        ax.set(xlabel="triangles (jittered UV sphere)", title=f"{kind} rays, one thread")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("time per ray (ns)")
    axes[0].legend(fontsize=8)
    fig.suptitle("Stage 3: naive is linear in the triangle count, a BVH about logarithmic")
    fig.tight_layout()
    fig.savefig(charts / "stage3-time-per-ray.png", dpi=110)
    plt.close(fig)


def accel_build_vs_trace(charts):
    rows = [r for r in read_rows(charts / "stage3-accel.csv") if r["accel"] not in ("naive",)]
    fig, ax = plt.subplots(figsize=(8, 4.8))
    for accel, (style, colour) in ACCEL_STYLE.items():
        mine = [r for r in rows if r["accel"] == accel and int(r["triangles"]) >= 900]
        if not mine:
            continue
        ax.loglog([float(r["build_ms"]) for r in mine], [float(r["incoherent_ns_per_ray"]) for r in mine], style[0],
                  color=colour, label=accel, ms=7)
        for r in mine:
            ax.annotate(r["mesh"].replace("sphere ", ""), (float(r["build_ms"]), float(r["incoherent_ns_per_ray"])),
                        fontsize=7, color=colour, xytext=(4, 2), textcoords="offset points")
    ax.set(xlabel="build time (ms)", ylabel="time per incoherent ray (ns)",
           title="Stage 3: build cost against traversal speed, per builder and mesh")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(charts / "stage3-build-vs-trace.png", dpi=110)
    plt.close(fig)


ESTIMATOR_STYLE = {"uniform": ("v-", "tab:gray"), "cosine": ("s-", "tab:olive"), "brdf": ("^-", "tab:blue"),
                   "light": ("o-", "tab:red")}


def direct_error_vs_time(charts):
    rows = read_rows(charts / "stage4-direct.csv")
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = plt.subplots(1, len(scenes), figsize=(10, 4.4), sharey=True)
    for ax, scene in zip(axes, scenes):
        for estimator, (style, colour) in ESTIMATOR_STYLE.items():
            mine = [r for r in rows if r["scene"] == scene and r["estimator"] == estimator]
            ax.loglog([float(r["seconds"]) for r in mine], [float(r["rmse"]) for r in mine], style, color=colour,
                      label=estimator, ms=4)
        ax.set(xlabel="render time (s), 1 to 256 spp", title=f"{scene}")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("RMSE against the converged reference")
    axes[0].legend(fontsize=8)
    fig.suptitle("Stage 4: direct lighting, error against time for four estimators")
    fig.tight_layout()
    fig.savefig(charts / "stage4-direct-error-vs-time.png", dpi=110)
    plt.close(fig)


def estimator_pictures(root, renders):
    """Tiles the four stage-4 renders (small/large light by light/BRDF sampling) into one picture."""
    names = [["small-light", "small-brdf"], ["large-light", "large-brdf"]]
    first = plt.imread(renders / "small-light.png")
    height, width = first.shape[:2]
    fig = plt.figure(figsize=(2 * width / 100, 2 * height / 100), dpi=100)
    for row, pair in enumerate(names):
        for col, name in enumerate(pair):
            ax = fig.add_axes([col / 2, 1 - (row + 1) / 2, 0.5, 0.5])
            ax.imshow(plt.imread(renders / f"{name}.png"), interpolation="nearest")
            ax.set_axis_off()
    fig.savefig(root / "docs" / "images" / "stage4-estimators.png", dpi=100)
    plt.close(fig)


def main(root):
    charts = pathlib.Path(root) / "docs" / "charts"
    sphere_precision(charts)
    offset_vs_scale(charts)
    accel_time_per_ray(charts)
    accel_build_vs_trace(charts)
    direct_error_vs_time(charts)
    renders = pathlib.Path(root) / "build" / "stage4-renders"
    if renders.exists():
        estimator_pictures(pathlib.Path(root), renders)
    print(f"charts written to {charts}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
