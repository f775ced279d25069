#!/usr/bin/env bash
# Runs each fuzz target for SECONDS (default 60) from the seed corpus and the kept findings, and
# fails on any crash, leak or sanitizer report. New inputs go to a scratch folder, never into the
# repository. Usage: tests/fuzz/run.sh [SECONDS] (after cmake --workflow --preset fuzz).
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-60}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for kind in scene obj batch merge image; do
  mkdir -p "$scratch/$kind"
  echo "fuzz: ${kind}_fuzzer for ${seconds} s"
  # The first folder receives new inputs; the others are only read. Crash inputs go to $scratch.
  build/fuzz/bin/${kind}_fuzzer -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="$scratch/" -print_final_stats=1 \
    "$scratch/$kind" "tests/fuzz/corpus/$kind" "tests/fuzz/regressions/$kind" 2>&1 | tail -n 25 \
    || { echo "fuzz: ${kind}_fuzzer found a problem; its input is in the log above"; exit 1; }
done
