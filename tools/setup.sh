#!/usr/bin/env bash
# Installs the Debian packages this framework needs, and only the ones that are missing.
#   tools/setup.sh          install what is missing (apt-get update first; as root or via sudo)
#   tools/setup.sh --check  list what is missing; exit 1 if anything is
# Does nothing, and asks for no privileges, when everything is already installed.
set -euo pipefail

packages=(
  cmake ninja-build g++ python3   # build, test runner, solution-marker check
  libglm-dev                      # vector math
  libstb-dev                      # stb_image_write (PNG)
  libtinyobjloader-dev            # OBJ meshes
  libtinyexr-dev                  # OpenEXR output
  nlohmann-json3-dev              # scene files
  libcli11-dev                    # command lines
  libpcg-cpp-dev                  # PCG random numbers
  libgtest-dev                    # unit tests
  libbenchmark-dev                # benchmarks
  libembree-dev                   # Embree: the production ceiling in the stage-3 benchmarks (optional to the build)
  python3-matplotlib              # charts (tools/make-charts.sh)
  python3-numpy                   # the grader's image statistics (tools/grade.py)
  bubblewrap                      # the grader's sandbox (tools/grading/sandbox.py)
  clang libclang-rt-14-dev        # libFuzzer for the fuzz targets (preset fuzz, tests/fuzz/run.sh)
  ccache mold                     # optional build accelerators: compiler cache, fast linker (cmake/BuildSpeed.cmake)
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ "${1:-}" = "--check" ]; then
  if [ ${#missing[@]} -gt 0 ]; then echo "setup: missing: ${missing[*]}"; exit 1; fi
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present, nothing to do"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "setup: need root or sudo to install: ${missing[*]}" >&2
  exit 1
fi

echo "setup: installing ${missing[*]}"
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
