#!/usr/bin/env bash
# Regenerates every chart in docs/charts/ from a fresh measurement: builds the release preset,
# runs the measuring programs (CSV), then plots them (PNG). Run from anywhere:
#   tools/make-charts.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
cmake --preset release >/dev/null
cmake --build --preset release --target sphere_precision offset_vs_scale triangle_leaks stage2_pictures accel_scaling
build/release/bin/sphere_precision docs/charts/stage1-sphere-precision.csv
build/release/bin/offset_vs_scale docs/charts/stage2-offset-vs-scale.csv
build/release/bin/triangle_leaks docs/charts/stage2-triangle-leaks.csv  # the table in docs/stage2.md
build/release/bin/stage2_pictures "$root"   # docs/images/stage2-acne.png, stage2-cracks.png
build/release/bin/accel_scaling docs/charts/stage3-accel.csv  # about 20 s; prints the ratios of docs/stage3.md
/usr/bin/python3 tools/plot_charts.py "$root"
