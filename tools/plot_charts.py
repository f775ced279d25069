#!/usr/bin/python3
"""Turns the CSV files in docs/charts/ into the PNG charts beside them.

Run through tools/make-charts.sh, which first regenerates the CSV. Needs Debian's matplotlib
(python3-matplotlib), hence /usr/bin/python3 rather than whichever python3 is first on PATH.
"""
import csv
import pathlib
import sys

import numpy as np

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


def filter_aliasing(charts):
    rows = read_rows(charts / "stage1-filter-aliasing.csv")
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for r in rows:
        aliasing, passband = float(r["aliasing"]), float(r["passband"])
        left.plot(aliasing, passband, "o", ms=8)
        left.annotate(r["filter"], (aliasing, passband), textcoords="offset points", xytext=(6, 4), fontsize=9)
    left.plot([0.0], [1.0], "k*", ms=10)
    left.annotate("ideal (sinc)", (0.0, 1.0), textcoords="offset points", xytext=(6, -10), fontsize=9)
    left.set(xlabel="aliasing: energy folded back from above Nyquist (share of the signal's)",
             ylabel="sharpness: passband contrast kept", title="Zone plate, 256 x 256, 256 spp")
    left.grid(True, alpha=0.3)
    names = [r["filter"] for r in rows]
    right.bar(names, [float(r["seconds"]) for r in rows], color="#2471a3")
    right.set(ylabel="render time (s, 2 threads)", title="Cost of sampling the filter by inversion")
    right.grid(True, axis="y", alpha=0.3)
    fig.suptitle("Stage 1: pixel reconstruction filters trade aliasing against blur")
    fig.tight_layout()
    fig.savefig(charts / "stage1-filter-aliasing.png", dpi=110)
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
               "sah": ("D-", "#2471a3"), "sah-wide-slots": ("P:", "#a569bd"), "sah-wide": ("P-", "#6c3483"),
               "sah-wide-compact": ("*-.", "#1f618d"), "embree": ("x--", "#17a589")}


def each_accel(rows, keep=lambda r: True):
    """(accel, style, colour, its rows that `keep` keeps), for each accelerator that has any."""
    for accel, (style, colour) in ACCEL_STYLE.items():
        mine = [r for r in rows if r["accel"] == accel and keep(r)]
        if mine:
            yield accel, style, colour, mine


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def accel_time_per_ray(charts):
    rows = [r for r in read_rows(charts / "stage3-accel.csv") if r["mesh"] != "bunny"]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), sharey=True)
    for ax, kind in zip(axes, ("incoherent", "coherent")):
        for accel, style, colour, mine in each_accel(rows):
            ax.loglog([int(r["triangles"]) for r in mine], [float(r[f"{kind}_ns_per_ray"]) for r in mine], style,
                      color=colour, label=accel)
        ax.set(xlabel="triangles (jittered UV sphere)", title=f"{kind} rays, one thread")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("time per ray (ns)")
    axes[0].legend(fontsize=8)
    fig.suptitle("Stage 3: naive is linear in the triangle count, a BVH about logarithmic")
    save(fig, charts / "stage3-time-per-ray.png")


def accel_build_vs_trace(charts):
    rows = [r for r in read_rows(charts / "stage3-accel.csv") if r["accel"] not in ("naive",)]
    fig, ax = plt.subplots(figsize=(8, 4.8))
    for accel, style, colour, mine in each_accel(rows, lambda r: int(r["triangles"]) >= 900):
        ax.loglog([float(r["build_ms"]) for r in mine], [float(r["incoherent_ns_per_ray"]) for r in mine], style[0],
                  color=colour, label=accel, ms=7)
        for r in mine:
            ax.annotate(r["mesh"].replace("sphere ", ""), (float(r["build_ms"]), float(r["incoherent_ns_per_ray"])),
                        fontsize=7, color=colour, xytext=(4, 2), textcoords="offset points")
    ax.set(xlabel="build time (ms)", ylabel="time per incoherent ray (ns)",
           title="Stage 3: build cost against traversal speed, per builder and mesh")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, charts / "stage3-build-vs-trace.png")


def accel_memory_vs_speed(charts):
    rows = [r for r in read_rows(charts / "stage3-accel.csv")
            if r["accel"] != "naive" and r["mesh"] in ("bunny", "sphere 1e6")]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4))
    for ax, mesh in zip(axes, ("bunny", "sphere 1e6")):
        for accel, style, colour, mine in each_accel(rows, lambda r: r["mesh"] == mesh):
            ax.plot([float(r["bytes_per_triangle"]) for r in mine], [float(r["incoherent_ns_per_ray"]) for r in mine],
                    style[0], color=colour, label=accel, ms=9)
        ax.axvline(64, color="grey", lw=0.8, ls=":")
        ax.text(65, ax.get_ylim()[1] * 0.95, "64 bytes", color="grey", fontsize=8, va="top")
        ax.set(xlabel="mesh + structure, bytes per triangle", title=f"{mesh}, incoherent rays, one thread")
        ax.set_ylim(bottom=0)
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("time per ray (ns)")
    axes[0].legend(fontsize=8)
    fig.suptitle("Stage 3: memory against speed (compact packs read their corners from the mesh)")
    save(fig, charts / "stage3-memory-vs-speed.png")


ESTIMATOR_STYLE = {"uniform": ("v-", "tab:gray"), "cosine": ("s-", "tab:olive"), "brdf": ("^-", "tab:blue"),
                   "light": ("o-", "tab:red"), "light (solid angle)": ("D--", "tab:purple")}


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
    fig.suptitle("Stage 4: direct lighting, error against time for four estimators (light: rectangle by area or solid angle)")
    fig.tight_layout()
    fig.savefig(charts / "stage4-direct-error-vs-time.png", dpi=110)
    plt.close(fig)


def environment_sampling(charts):
    rows = read_rows(charts / "stage4-environment.csv")
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for strategy, (style, colour) in {"importance": ("o-", "tab:red"), "uniform": ("s-", "tab:grey")}.items():
        mine = [r for r in rows if r["strategy"] == strategy]
        ax.loglog([int(r["spp"]) for r in mine], [float(r["rmse"]) for r in mine], style, color=colour,
                  label=f"{strategy} ({'luminance x sin theta table' if strategy == 'importance' else 'over the sphere'})",
                  ms=4)
    ax.set(xlabel="samples per pixel", ylabel="RMSE against the converged reference",
           title="Stage 4: environment.json, light sampling of the sky and sun")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(charts / "stage4-environment.png", dpi=110)
    plt.close(fig)


def adaptive_error_vs_time(charts):
    rows = read_rows(charts / "stage5-adaptive.csv")
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = plt.subplots(1, len(scenes), figsize=(10, 4.4))
    for ax, scene in zip(axes, scenes):
        for method, (style, colour) in {"uniform": ("s-", "tab:grey"), "adaptive": ("o-", "tab:red")}.items():
            mine = [r for r in rows if r["scene"] == scene and r["method"] == method]
            ax.loglog([float(r["seconds"]) for r in mine], [float(r["rmse"]) for r in mine], style, color=colour,
                      label=method + (" (tolerance 0.4 to 0.025, at most 1024 spp)" if method == "adaptive"
                                      else " (4 to 1024 spp)"), ms=4)
            if method == "adaptive":
                for r in mine:
                    ax.annotate(r["parameter"], (float(r["seconds"]), float(r["rmse"])), fontsize=7,
                                textcoords="offset points", xytext=(4, 4))
        ax.set(xlabel="wall time on 2 cores (s)", title=scene)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("RMSE against the reference")
    fig.suptitle("Stage 5: adaptive sampling against the same paths in every pixel (MIS, Sobol)")
    fig.tight_layout()
    fig.savefig(charts / "stage5-adaptive.png", dpi=110)
    plt.close(fig)


PATH_STYLE = {("naive", "sobol"): ("v-", "tab:grey"),
              ("rr", "sobol"): ("^-", "tab:purple"),
              ("nee", "sobol"): ("s-", "tab:blue"),
              ("mis", "sobol"): ("o-", "tab:red"),
              ("mis", "independent"): ("o--", "tab:orange")}


def path_chart(charts, x, xlabel, title, png, guides):
    """One stage-5 chart from stage5-paths.csv: RMSE against column `x`, log-log, one line per
    integrator and sampler; `guides(ax, rows)` draws the chart's own reference lines."""
    rows = read_rows(charts / "stage5-paths.csv")
    fig, ax = plt.subplots(figsize=(7.5, 5))
    for (integrator, sampler), (style, colour) in PATH_STYLE.items():
        mine = [r for r in rows if r["integrator"] == integrator and r["sampler"] == sampler]
        if mine:
            ax.loglog([float(r[x]) for r in mine], [float(r["rmse"]) for r in mine], style, color=colour,
                      label=f"{integrator}, {sampler}", ms=4)
    guides(ax, rows)
    ax.set(xlabel=xlabel, ylabel="RMSE against the converged reference", title=title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(charts / png, dpi=110)
    plt.close(fig)


def path_error_vs_time(charts):
    def target(ax, rows):
        ax.axhline(0.005, color="black", lw=0.8, ls=":")
        ax.axvline(20.0, color="black", lw=0.8, ls=":")
        ax.text(1.02 * 20.0, 0.3, "20 s", fontsize=8)
        ax.text(ax.get_xlim()[0] * 1.1, 0.0053, "RMSE 0.005", fontsize=8)

    path_chart(charts, "seconds", "wall time on 2 cores (s), spp doubling from 1",
               "Stage 5: Cornell box 256 x 256, error against time", "stage5-error-vs-time.png", target)


def path_convergence(charts):
    def inverse_square_root(ax, rows):
        anchor = [r for r in rows if r["integrator"] == "mis" and r["sampler"] == "independent"][0]
        spp = [1, 4096]
        ax.loglog(spp, [float(anchor["rmse"]) * n ** -0.5 for n in spp], color="black", lw=0.8, ls=":",
                  label="N^-1/2 (through mis, independent at 1 spp)")

    path_chart(charts, "spp", "samples per pixel N", "Stage 5: Cornell box 256 x 256, convergence",
               "stage5-convergence.png", inverse_square_root)


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


def srgb(linear):
    """Linear radiance to display values: clamp to [0, 1], then the sRGB curve (IEC 61966-2-1)."""
    x = np.clip(linear, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)


def cornell_pictures(root, render):
    """The README's Cornell box render beside the converged reference, for docs/stage5.md."""
    sys.path.insert(0, str(pathlib.Path(__file__).parent))
    from pfm import read_pfm  # noqa: E402  (a sibling tool)
    images = [read_pfm(render), read_pfm(root / "assets" / "references" / "cornell-box-256.pfm")]
    titles = ["256 spp, MIS, Sobol (the README's first command)", "reference, 32,768 spp"]
    height, width = images[0].shape[:2]
    fig = plt.figure(figsize=(2 * width / 100, (height + 24) / 100), dpi=100)
    for col, (image, title) in enumerate(zip(images, titles)):
        ax = fig.add_axes([col / 2, 0, 0.5, height / (height + 24)])
        ax.imshow(srgb(image), interpolation="nearest")
        ax.set_axis_off()
        fig.text(col / 2 + 0.25, 1 - 12 / (height + 24), title, ha="center", va="center", fontsize=7)
    fig.savefig(root / "docs" / "images" / "stage5-cornell-box.png", dpi=100)
    plt.close(fig)

TRANSPORT_STYLE = {"pt": ("o-", "tab:grey"), "lt": ("v-", "tab:purple"), "bdpt": ("s-", "tab:blue"),
                   "sppm": ("D-", "tab:red"), "vcm": ("*-", "tab:green"), "mlt": ("^-", "tab:orange"),
                   "pssmlt": ("<--", "tab:brown")}
TRANSPORT_REGION = {"cornell-box": "whole image", "caustic": "the caustic in front of the ball",
                    "caustic-through-glass": "the caustic seen through a pane of glass",
                    "light-through-gap": "floor and wall left of the gap", "door-ajar": "whole image"}
TRANSPORT_TITLE = {6: "Stage 6: error against time where path tracing fails (1, 2, 4, ... spp or SPPM passes)",
                   7: "Stage 7: every method of stages 6 and 7 (1, 2, 4, ... spp, passes, iterations or mutations "
                      "per pixel)"}


def transport_error_vs_time(charts, stage):
    """Stages 6 and 7: RMSE over each scene's region against wall time, one panel per scene."""
    if not (charts / f"stage{stage}-error-vs-time.csv").exists():
        return
    rows = read_rows(charts / f"stage{stage}-error-vs-time.csv")
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = plt.subplots(1, len(scenes), figsize=(4 * len(scenes), 4.2))
    for ax, scene in zip(axes, scenes):
        for method, (style, colour) in TRANSPORT_STYLE.items():
            mine = [r for r in rows if r["scene"] == scene and r["method"] == method]
            if mine:
                ax.loglog([float(r["seconds"]) for r in mine], [float(r["region_rmse"]) for r in mine], style,
                          color=colour, label=method, ms=4)
        ax.set(xlabel="wall time on 2 cores (s)", title=f"{scene}\n({TRANSPORT_REGION.get(scene, '')})")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("RMSE against the converged reference")
    fig.suptitle(TRANSPORT_TITLE[stage])
    fig.tight_layout()
    fig.savefig(charts / f"stage{stage}-error-vs-time.png", dpi=110)
    plt.close(fig)


def transport_pictures(root, renders, charts, stage, scenes=None):
    """Equal-time pictures of stage 6 or 7: per scene, each method's render of about 2 s side by side."""
    sys.path.insert(0, str(pathlib.Path(__file__).parent))
    from pfm import read_pfm  # noqa: E402  (a sibling tool)
    rows = [r for r in read_rows(charts / f"stage{stage}-error-vs-time.csv") if r["picture"] == "1"]
    for scene in dict.fromkeys(r["scene"] for r in rows):
        if scenes and scene not in scenes:
            continue
        mine = [r for r in rows if r["scene"] == scene]
        images = [read_pfm(renders / f"stage{stage}-{scene}-{r['method']}.pfm") for r in mine]
        height, width = images[0].shape[:2]
        scale = max(1, 256 // width)
        fig = plt.figure(figsize=(len(images) * scale * width / 100, (scale * height + 24) / 100), dpi=100)
        for col, (image, r) in enumerate(zip(images, mine)):
            ax = fig.add_axes([col / len(images), 0, 1 / len(images), scale * height / (scale * height + 24)])
            ax.imshow(srgb(image), interpolation="nearest")
            ax.set_axis_off()
            unit = {"sppm": "passes", "vcm": "iterations", "mlt": "mpp", "pssmlt": "mpp"}.get(r["method"], "spp")
            fig.text((col + 0.5) / len(images), 1 - 12 / (scale * height + 24),
                     f"{r['method']}: {r['spp']} {unit}, {float(r['seconds']):.1f} s", ha="center", va="center",
                     fontsize=8)
        fig.savefig(root / "docs" / "images" / f"stage{stage}-{scene}.png", dpi=100)
        plt.close(fig)


def mutation_map_picture(root, renders):
    """Stage 7: an MLT render of the door-ajar scene beside its mutation map."""
    from PIL import Image  # noqa: E402  (Debian's python3-pil, as for the other pictures)
    images = [Image.open(renders / "door-mlt.png"), Image.open(renders / "door-map.png")]
    width, height = images[0].size
    fig = plt.figure(figsize=(2 * width / 100, (height + 24) / 100), dpi=100)
    titles = ["multiplexed MLT, 64 mutations per pixel", "where its chains stepped (log scale)"]
    for col, (image, title) in enumerate(zip(images, titles)):
        ax = fig.add_axes([col / 2, 0, 1 / 2, height / (height + 24)])
        ax.imshow(image, interpolation="nearest")
        ax.set_axis_off()
        fig.text((col + 0.5) / 2, 1 - 12 / (height + 24), title, ha="center", va="center", fontsize=7)
    fig.savefig(root / "docs" / "images" / "stage7-mutation-map.png", dpi=100)
    plt.close(fig)


def main(root):
    charts = pathlib.Path(root) / "docs" / "charts"
    sphere_precision(charts)
    filter_aliasing(charts)
    offset_vs_scale(charts)
    accel_time_per_ray(charts)
    accel_build_vs_trace(charts)
    accel_memory_vs_speed(charts)
    direct_error_vs_time(charts)
    environment_sampling(charts)
    path_error_vs_time(charts)
    adaptive_error_vs_time(charts)
    path_convergence(charts)
    transport_error_vs_time(charts, 6)
    transport_error_vs_time(charts, 7)
    renders = pathlib.Path(root) / "build" / "stage4-renders"
    if renders.exists():
        estimator_pictures(pathlib.Path(root), renders)
    cornell = pathlib.Path(root) / "build" / "stage5-renders" / "cornell-box.pfm"
    if cornell.exists():
        cornell_pictures(pathlib.Path(root), cornell)
    transport = pathlib.Path(root) / "build" / "stage6-renders"
    if transport.exists():
        transport_pictures(pathlib.Path(root), transport, charts, 6)
    transport = pathlib.Path(root) / "build" / "stage7-renders"
    if transport.exists():
        transport_pictures(pathlib.Path(root), transport, charts, 7, scenes={"door-ajar", "caustic-through-glass"})
        if (transport / "door-map.png").exists():
            mutation_map_picture(pathlib.Path(root), transport)
    print(f"charts written to {charts}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
