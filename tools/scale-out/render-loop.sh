#!/usr/bin/env bash
# The plain shell loop: BATCHES sample batches of SAMPLES each, rendered on this machine, JOBS
# processes at a time (default: one per core), each writing OUT/bI.json with samples
# [I * SAMPLES, (I + 1) * SAMPLES). Then `merge --out IMAGE OUT` adds them (docs/scale-out.md).
#
#   JOBS=4 tools/scale-out/render-loop.sh OUT BATCHES SAMPLES PROGRAM [PROGRAM'S FLAGS...]
#   tools/scale-out/render-loop.sh parts 8 32 build/release/bin/stage5 \
#       --scene assets/scenes/cornell-box.json --width 256 --height 256 --threads 1
#
# Batches run in rounds of JOBS (equal batches take about equally long). A batch's output goes to
# OUT/bI.log; the exit code is 1 if any batch failed, naming it.
set -uo pipefail
if (($# < 4)); then
  echo "usage: render-loop.sh OUT BATCHES SAMPLES PROGRAM [FLAGS...]" >&2
  exit 2
fi
out=$1 batches=$2 samples=$3
shift 3
jobs=${JOBS:-$(nproc)}
mkdir -p "$out" || exit 1

failed=0
for ((first = 0; first < batches; first += jobs)); do
  pids=()
  for ((i = first; i < first + jobs && i < batches; i++)); do
    "$@" --sample-range $((i * samples)):$(((i + 1) * samples)) --out "$out/b$i.json" >"$out/b$i.log" 2>&1 &
    pids+=($!)
  done
  for ((k = 0; k < ${#pids[@]}; k++)); do
    if ! wait "${pids[k]}"; then
      echo "render-loop.sh: batch $((first + k)) failed: $(tail -n 1 "$out/b$((first + k)).log")" >&2
      failed=1
    fi
  done
done
exit $failed
