#!/usr/bin/env bash
# Instructions per unit of work for each of the given commits, the figures of the speed ladders in
# docs/stage3.md and docs/stage5.md. Unlike time, an instruction count does not move when the
# machine is busy, so a step of 1 % shows up as 1 %. Each commit is built (release preset) in a git
# worktree of its own under WORK and run under callgrind (valgrind's instruction counter):
#  - the Cornell box, 64 x 64 at 16 spp, one thread: instructions per path (65,536 paths; the scene
#    and BVH set-up, under 0.5 % of the total, is included);
#  - the bunny (stage3 --wide, 64 x 64): instructions per camera sample, as the difference between
#    9 spp and 1 spp, so the BVH build drops out.
#
#   benchmarks/count_instructions.sh REV...        e.g. benchmarks/count_instructions.sh HEAD~3 HEAD
#
# About a minute per commit once built (callgrind runs about 50 times slower than the program).
set -euo pipefail
[[ $# -ge 1 ]] || { echo "usage: $0 REV..." >&2; exit 2; }
command -v valgrind > /dev/null || { echo "$0: needs valgrind (apt-get install valgrind)" >&2; exit 1; }
repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
work=${WORK:-/tmp/compare-builds}
mkdir -p "$work"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

instructions() {  # PROGRAM ARGS... -> the instructions it executed
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "$@" 2>&1 >/dev/null | sed -n 's/.*Collected : \([0-9]*\)$/\1/p'
}

for rev in "$@"; do
  commit=$(git -C "$repo" rev-parse --verify "$rev^{commit}")
  tree="$work/$commit"
  [[ -d "$tree" ]] || git -C "$repo" worktree add --detach "$tree" "$commit" > /dev/null
  (cd "$tree" && cmake --preset release > /dev/null && cmake --build --preset release --target stage3 stage5 > /dev/null)
  bin="$tree/build/release/bin"
  cornell=$(instructions "$bin/stage5" --scene "$repo/assets/scenes/cornell-box.json" --out "$out/c.pfm" \
    --width 64 --height 64 --spp 16 --threads 1)
  bunny() { instructions "$bin/stage3" --scene "$repo/assets/scenes/bunny.json" --out "$out/b.pfm" \
    --width 64 --height 64 --spp "$1" --threads 1 --wide; }
  b1=$(bunny 1)
  b9=$(bunny 9)
  printf '%s  Cornell box: %6d instructions per path   bunny (4-wide): %5d per camera sample\n' \
    "$(git -C "$repo" log -1 --format='%h %<(40,trunc)%s' "$commit")" $((cornell / 65536)) $(((b9 - b1) / (8 * 4096)))
done
