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


def main(root):
    charts = pathlib.Path(root) / "docs" / "charts"
    sphere_precision(charts)
    offset_vs_scale(charts)
    print(f"charts written to {charts}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
