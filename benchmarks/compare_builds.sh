#!/usr/bin/env bash
# The speed of two commits side by side, in one run: builds each (release preset, in a git worktree
# of its own under WORK) and then alternates their measurements, so that whatever else the machine
# does falls on both alike. Measured: the Cornell box's paths per second (path_error_vs_time
# --throughput: MIS with Sobol samples, 1 and 2 threads) and the BVH's rays per second on the bunny
# (stage3, one thread, the binary SAH tree and the 4-wide one).
#
#   benchmarks/compare_builds.sh [--runs N] BASE_REV [NEW_REV]     (NEW_REV defaults to HEAD)
#
# WORK (default /tmp/compare-builds) keeps the builds, so a second call only measures.
set -euo pipefail
runs=3
if [[ "${1:-}" == "--runs" ]]; then runs=$2; shift 2; fi
[[ $# -ge 1 ]] || { echo "usage: $0 [--runs N] BASE_REV [NEW_REV]" >&2; exit 2; }
repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
work=${WORK:-/tmp/compare-builds}
mkdir -p "$work"

build() {  # REV -> prints the folder of its programs
  local commit tree
  commit=$(git -C "$repo" rev-parse --verify "$1^{commit}")
  tree="$work/$commit"
  if [[ ! -x "$tree/build/release/bin/stage3" || ! -x "$tree/build/release/bin/path_error_vs_time" ]]; then
    [[ -d "$tree" ]] || git -C "$repo" worktree add --detach "$tree" "$commit" > /dev/null
    (cd "$tree" && cmake --preset release > /dev/null &&
      cmake --build --preset release --target stage3 path_error_vs_time > /dev/null)
  fi
  echo "$tree/build/release/bin"
}

base=$(build "$1")
new=$(build "${2:-HEAD}")
scene="$repo/assets/scenes/bunny.json"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

for ((i = 1; i <= runs; ++i)); do
  for side in base new; do
    bin=${!side}
    "$bin/path_error_vs_time" --throughput | sed -n 's/^ *\([12]\) threads\? *: \([0-9.]*\) M paths.*/\1 \2/p' |
      while read -r threads rate; do echo "$side paths/s x1e6, $threads thread(s): $rate"; done
    for wide in "" --wide; do
      rate=$("$bin/stage3" --scene "$scene" --out "$out/bunny.pfm" --spp 16 --threads 1 $wide |
        awk '/rays\/s/ {n = $(NF - 2); u = $(NF - 1); print n * (u == "k" ? 1e-3 : u == "G" ? 1e3 : 1)}')
      echo "$side bunny rays/s x1e6, ${wide:-binary}: $rate"
    done
  done
done | tee "$out/all.txt"

# Besides each side's median, the median of the ratios of the runs made side by side (run i of new
# over run i of base): this machine has slow and fast spells of minutes, and a spell that covers
# more runs of one side moves its median, but not the ratio of two runs taken a few seconds apart.
echo "medians over $runs runs (base -> new; median of the paired ratios new/base):"
sed 's/: [0-9.]*$//' "$out/all.txt" | sed 's/^[a-z]* //' | sort -u | while read -r what; do
  values() { grep "^$1 $what:" "$out/all.txt" | sed 's/.*: //'; }
  median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
  ratio=$(paste <(values base) <(values new) | awk '{printf "%.3f\n", $2 / $1}' | median)
  echo "  $what: $(values base | median) -> $(values new | median)   (paired: ${ratio}x)"
done
