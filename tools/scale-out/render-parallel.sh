#!/usr/bin/env bash
# GNU parallel over ssh: BATCHES sample batches of SAMPLES each, spread over the hosts listed in
# HOSTS (GNU parallel's --sshloginfile: one "[cores/]host" per line, ":" for this machine). Each
# host needs this checkout, built, at the same absolute path; the hosts need not share a file
# system: each batch runs in a scratch folder on its host and its three files come back into OUT
# (a relative path) here (docs/scale-out.md).
#
#   tools/scale-out/render-parallel.sh HOSTS OUT BATCHES SAMPLES PROGRAM [PROGRAM'S FLAGS...]
#   tools/scale-out/render-parallel.sh hosts.txt parts 16 64 "$PWD/build/release/bin/stage5" \
#       --scene "$PWD/assets/scenes/cornell-box.json" --width 1920 --height 1080 --threads 0
#
# PROGRAM and every file its flags name must be absolute paths that exist on every host.
set -euo pipefail
if (($# < 5)); then
  echo "usage: render-parallel.sh HOSTS OUT BATCHES SAMPLES PROGRAM [FLAGS...]" >&2
  exit 2
fi
hosts=$1 out=$2 batches=$3 samples=$4
shift 4
case $out in /*) echo "render-parallel.sh: OUT must be a relative path (it is made on each host too)" >&2; exit 2 ;; esac
mkdir -p "$out"
command=$(printf '%q ' "$@")
# --controlmaster: one ssh connection per host, reused by its jobs. --workdir ...: a fresh scratch folder per job on its host, removed by --cleanup once --return has
# copied the batch back. --halt now,fail=1: the first failed batch stops the rest.
parallel --sshloginfile "$hosts" --controlmaster --workdir ... --halt now,fail=1 --cleanup \
  --return "$out/b{}.json" --return "$out/b{}.sum.pfm" --return "$out/b{}.count.pfm" \
  "mkdir -p $out && $command --sample-range \$(({} * $samples)):\$((({} + 1) * $samples)) --out $out/b{}.json" \
  ::: $(seq 0 $((batches - 1)))
