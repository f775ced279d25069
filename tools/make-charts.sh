#!/usr/bin/env bash
# Regenerates every chart in docs/charts/ from a fresh measurement: builds the release preset,
# runs the measuring programs (CSV), then plots them (PNG). Run from anywhere:
#   tools/make-charts.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
cmake --preset release >/dev/null
cmake --build --preset release --target sphere_precision
build/release/bin/sphere_precision docs/charts/stage1-sphere-precision.csv
/usr/bin/python3 tools/plot_charts.py "$root"
