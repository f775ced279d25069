#!/usr/bin/env bash
# The speed of two commits side by side, in one run: builds each (release preset, in a git worktree
# of its own under WORK) and then measures them together, so that whatever else the machine does
# falls on both alike. Measured, N rounds:
#  - one thread, the two builds AT THE SAME TIME, pinned one to each of cores 0 and 1, then again
#    with the cores swapped: the Cornell box's paths per second (stage5, MIS with Sobol samples,
#    128 x 128 at 64 spp), the BVH's rays per second on the bunny (stage3, the binary SAH tree
#    and the 4-wide one), and the photon renderers' samples per second: vertex connection and
#    merging on the Cornell box (stage7, 64 x 64, 64 iterations) and SPPM behind the pane of glass
#    (stage6, 128 x 96, 16 passes of 10^5 photons). The round's ratio is the geometric mean of the
#    two ratios new/base, which cancels a difference in speed between the cores; running together,
#    both builds meet the same spell of the machine (this one has slow spells of minutes, 0.60
#    against 0.74 M paths/s for one build, and at times one core slower than the other);
#  - two threads, the builds one after the other (path_error_vs_time --throughput, 256 x 256 at
#    64 spp, best of three): each run's ratio is taken with the other build's run next to it;
#  - the binary SAH tree's build on the 10^6-triangle mesh, on both cores, one after the other
#    (stage3_bench Build/sah/6, the median of three builds): the ratio is base time / new time.
# Printed: each side's median and the median of the rounds' ratios.
#
#   benchmarks/compare_builds.sh [--runs N] BASE_REV [NEW_REV]     (NEW_REV defaults to HEAD)
#
# WORK (default /tmp/compare-builds) keeps the builds, so a second call only measures. Needs two
# cores and taskset (util-linux) for the one-thread pairs.
set -euo pipefail
runs=3
if [[ "${1:-}" == "--runs" ]]; then runs=$2; shift 2; fi
[[ $# -ge 1 ]] || { echo "usage: $0 [--runs N] BASE_REV [NEW_REV]" >&2; exit 2; }
[[ $(nproc) -ge 2 ]] && command -v taskset > /dev/null ||
  { echo "$0: needs two cores and taskset for the one-thread pairs" >&2; exit 1; }
repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
work=${WORK:-/tmp/compare-builds}
mkdir -p "$work"

build() {  # REV -> prints the folder of its programs
  local commit tree
  commit=$(git -C "$repo" rev-parse --verify "$1^{commit}")
  tree="$work/$commit"
  if [[ ! -x "$tree/build/release/bin/stage3" || ! -x "$tree/build/release/bin/stage5" ||
        ! -x "$tree/build/release/bin/stage6" || ! -x "$tree/build/release/bin/stage7" ||
        ! -x "$tree/build/release/bin/path_error_vs_time" || ! -x "$tree/build/release/bin/stage3_bench" ]]; then
    [[ -d "$tree" ]] || git -C "$repo" worktree add --detach "$tree" "$commit" > /dev/null
    (cd "$tree" && cmake --preset release > /dev/null &&
      cmake --build --preset release --target stage3 stage5 stage6 stage7 path_error_vs_time stage3_bench > /dev/null)
  fi
  echo "$tree/build/release/bin"
}

base=$(build "$1")
new=$(build "${2:-HEAD}")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# The rate a program prints last ("... 798 ksamples/s", "... 5.85 M rays/s"), in millions.
rate() {
  awk '/\/s$/ { if ($(NF - 1) ~ /^[kMG]$/) { n = $(NF - 2); u = $(NF - 1) } else { n = $(NF - 1); u = substr($NF, 1, 1) }
               r = n * (u == "k" ? 1e-3 : u == "M" ? 1 : u == "G" ? 1e3 : 1e-6) } END { print r }'
}
# CORE WHAT BIN: one measurement of WHAT by the build folder BIN on one thread, pinned to CORE.
measure() {
  local core=$1 what=$2 bin=$3
  case $what in
    cornell) taskset -c "$core" "$bin/stage5" --scene "$repo/assets/scenes/cornell-box.json" --out "$out/$core.pfm" \
               --width 128 --height 128 --spp 64 --threads 1 2>&1 | rate ;;
    binary | wide) taskset -c "$core" "$bin/stage3" --scene "$repo/assets/scenes/bunny.json" --out "$out/$core.pfm" \
               --spp 16 --threads 1 $([[ $what == wide ]] && echo --wide) 2>&1 | rate ;;
    vcm) taskset -c "$core" "$bin/stage7" --scene "$repo/assets/scenes/cornell-box.json" --out "$out/$core.pfm" \
               --width 64 --height 64 --spp 64 --threads 1 2>&1 | rate ;;
    sppm) taskset -c "$core" "$bin/stage6" --method sppm --scene "$repo/assets/scenes/caustic-through-glass.json" \
               --out "$out/$core.pfm" --width 128 --height 96 --spp 16 --threads 1 2>&1 | rate ;;
  esac
}
# WHAT: base and new at the same time on cores 0 and 1, then on 1 and 0; prints the four rates and
# the round's ratio, the geometric mean of the two ratios new/base.
pair() {
  local what=$1 b0 b1 n0 n1
  measure 0 "$what" "$base" > "$out/b0" & measure 1 "$what" "$new" > "$out/n1" & wait
  measure 1 "$what" "$base" > "$out/b1" & measure 0 "$what" "$new" > "$out/n0" & wait
  b0=$(cat "$out/b0") b1=$(cat "$out/b1") n0=$(cat "$out/n0") n1=$(cat "$out/n1")
  awk -v what="$what" -v b0="$b0" -v b1="$b1" -v n0="$n0" -v n1="$n1" \
    'BEGIN { printf "%s, 1 thread: base %s %s new %s %s ratio %.4f\n", what, b0, b1, n1, n0, sqrt((n1 / b0) * (n0 / b1)) }'
}

for ((i = 1; i <= runs; ++i)); do
  for what in cornell binary wide vcm sppm; do pair "$what"; done
  for side in base new; do
    bin=${!side}
    "$bin/path_error_vs_time" --throughput | sed -n 's/^ *2 threads: \([0-9.]*\) M paths.*/\1/p' |
      while read -r rate; do echo "cornell, 2 threads ($side): $rate"; done
    "$bin/stage3_bench" --benchmark_filter='^Build/sah/6(/real_time)?$' --benchmark_repetitions=3 \
      --benchmark_report_aggregates_only=true --benchmark_format=csv 2> /dev/null |
      awk -F, '/_median"/ { print "build, 2 threads ('"$side"'): " $3 }'
  done
done | tee "$out/all.txt"

median() { sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
echo "medians over $runs rounds (base -> new; median of the rounds' ratios new/base):"
for what in cornell binary wide vcm sppm; do
  line="$what, 1 thread"
  b=$(grep "^$line:" "$out/all.txt" | awk '{print $5; print $6}' | median)
  n=$(grep "^$line:" "$out/all.txt" | awk '{print $8; print $9}' | median)
  r=$(grep "^$line:" "$out/all.txt" | awk '{print $11}' | median)
  case $what in cornell) unit=paths ;; binary | wide) unit=rays ;; *) unit=samples ;; esac
  echo "  $line (M $unit/s, together): $b -> $n   (${r}x)"
done
b=$(grep '^cornell, 2 threads (base)' "$out/all.txt" | sed 's/.*: //')
n=$(grep '^cornell, 2 threads (new)' "$out/all.txt" | sed 's/.*: //')
r=$(paste <(echo "$b") <(echo "$n") | awk '{printf "%.4f\n", $2 / $1}' | median)
echo "  cornell, 2 threads (M paths/s, one after the other): $(echo "$b" | median) -> $(echo "$n" | median)   (${r}x)"
b=$(grep '^build, 2 threads (base)' "$out/all.txt" | sed 's/.*: //')
n=$(grep '^build, 2 threads (new)' "$out/all.txt" | sed 's/.*: //')
r=$(paste <(echo "$b") <(echo "$n") | awk '{printf "%.4f\n", $1 / $2}' | median)
echo "  10^6-triangle SAH build, 2 threads (ms, one after the other): $(echo "$b" | median) -> $(echo "$n" | median)   (${r}x faster)"
