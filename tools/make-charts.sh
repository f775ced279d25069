#!/usr/bin/env bash
# Regenerates every chart in docs/charts/ from a fresh measurement: builds the release preset,
# runs the measuring programs (CSV), then plots them (PNG). Run from anywhere:
#   tools/make-charts.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
cmake --preset release >/dev/null
cmake --build --preset release --target sphere_precision filter_aliasing offset_vs_scale triangle_leaks stage2_pictures accel_scaling \
  direct_error_vs_time path_error_vs_time environment_sampling adaptive_error_vs_time transport_error_vs_time \
  stage4 stage5 stage7
build/release/bin/sphere_precision docs/charts/stage1-sphere-precision.csv
build/release/bin/filter_aliasing docs/charts/stage1-filter-aliasing.csv docs/images  # about 15 s
build/release/bin/offset_vs_scale docs/charts/stage2-offset-vs-scale.csv
build/release/bin/triangle_leaks docs/charts/stage2-triangle-leaks.csv  # the table in docs/stage2.md
build/release/bin/stage2_pictures "$root"   # docs/images/stage2-acne.png, stage2-cracks.png
build/release/bin/accel_scaling docs/charts/stage3-accel.csv  # about 20 s; prints the ratios of docs/stage3.md
build/release/bin/direct_error_vs_time docs/charts/stage4-direct.csv  # about 90 s
build/release/bin/path_error_vs_time docs/charts/stage5-paths.csv  # about 15 minutes
build/release/bin/environment_sampling docs/charts/stage4-environment.csv  # about 20 s
build/release/bin/adaptive_error_vs_time docs/charts/stage5-adaptive.csv docs/images  # about 8 minutes
mkdir -p build/stage6-renders  # the equal-time pictures, tiled into docs/images/stage6-<scene>.png
build/release/bin/transport_error_vs_time 6 docs/charts/stage6-error-vs-time.csv build/stage6-renders  # about 8 minutes
mkdir -p build/stage7-renders  # the same with stage 7's methods and the door-ajar scene
build/release/bin/transport_error_vs_time 7 docs/charts/stage7-error-vs-time.csv build/stage7-renders  # about 18 minutes
build/release/bin/stage7 --scene assets/scenes/door-ajar.json --width 256 --height 192 --mode mlt \
  --mutations-per-pixel 64 --bootstrap 20000 --out build/stage7-renders/door-mlt.png \
  --mutation-map build/stage7-renders/door-map.png >/dev/null  # docs/images/stage7-mutation-map.png
build/release/bin/stage4 --scene assets/scenes/textures.json --spp 64 --out docs/images/stage4-textures.png
build/release/bin/stage5 --scene assets/scenes/environment.json --spp 256 --out docs/images/stage5-environment.png
mkdir -p build/stage4-renders  # the four renders tiled into docs/images/stage4-estimators.png
for light in small large; do
  for estimator in light brdf; do
    build/release/bin/stage4 --scene "assets/scenes/direct-$light-light.json" --spp 64 --estimator "$estimator" \
      --out "build/stage4-renders/$light-$estimator.png" >/dev/null
  done
done
build/release/bin/stage1 --scene assets/scenes/depth-of-field.json --out docs/images/stage1-depth-of-field.png
mkdir -p build/display  # one HDR render of the Cornell box under each display transform (docs/display.md)
build/release/bin/stage5 --scene assets/scenes/cornell-box.json --width 256 --height 256 --spp 128 --out build/display/cornell.json
for view in "default:" "gamma:--gamma 2.2" "bright:--exposure 1.5" "reinhard:--exposure 1.5 --tone reinhard --white 8" \
  "aces:--exposure 1.5 --tone aces"; do
  # shellcheck disable=SC2086  # the flags are meant to split
  build/release/bin/merge --out "docs/images/display-${view%%:*}.png" ${view#*:} build/display/cornell.json >/dev/null
done
mkdir -p build/stage5-renders  # the README's first render, beside the reference in docs/images/stage5-cornell-box.png
build/release/bin/stage5 --scene assets/scenes/cornell-box.json --out build/stage5-renders/cornell-box.pfm
/usr/bin/python3 tools/plot_charts.py "$root"
