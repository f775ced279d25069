#!/usr/bin/env bash
# Runs each fuzz target for SECONDS (default 60) from the seed corpus and the kept findings, and
# fails on any crash, leak or sanitizer report. New inputs go to a scratch folder, never into the
# repository. A fuzzer runs on one core, so as many run at once as there are cores (JOBS, default
# nproc): each still gets its full SECONDS. Usage: tests/fuzz/run.sh [SECONDS] [JOBS]
# (after cmake --workflow --preset fuzz).
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-60}
jobs=${2:-$(nproc)}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
kinds=(scene obj batch merge image)

fuzz_one() {  # fuzz_one KIND: runs KIND's fuzzer, its log in $scratch/KIND.log, its status in KIND.status
  local kind=$1
  mkdir -p "$scratch/$kind"
  # The first folder receives new inputs; the others are only read. Crash inputs go to $scratch.
  local status=0
  build/fuzz/bin/${kind}_fuzzer -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$scratch/$kind-" -print_final_stats=1 \
    "$scratch/$kind" "tests/fuzz/corpus/$kind" "tests/fuzz/regressions/$kind" > "$scratch/$kind.log" 2>&1 \
    || status=$?
  echo "$status" > "$scratch/$kind.status"
}

echo "fuzz: ${kinds[*]}, ${seconds} s each, ${jobs} at a time"
running=0
for kind in "${kinds[@]}"; do
  if (( running >= jobs )); then
    wait -n || true
    running=$((running - 1))
  fi
  fuzz_one "$kind" &
  running=$((running + 1))
done
wait

failed=()
for kind in "${kinds[@]}"; do
  echo "fuzz: ---- ${kind}_fuzzer"
  tail -n 25 "$scratch/$kind.log"
  [[ $(cat "$scratch/$kind.status") == 0 ]] || failed+=("$kind")
done
if (( ${#failed[@]} )); then
  for kind in "${failed[@]}"; do
    echo "fuzz: ${kind}_fuzzer found a problem; its input is in its log above"
  done
  exit 1
fi
