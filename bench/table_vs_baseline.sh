#!/usr/bin/env bash
# The default table (worst case and bound) against the paper's frames as an older build computes
# them: both built here, run alternately (rounds times each, so this VM's drift falls on both
# alike), each run's wall time and peak RSS; then whether any row's MTS lies below the older
# build's own worst case. The baseline defaults to 01e7a02, the main the worst case's cost was
# first measured on (its `table --set sampling=paper` is the time the default table is held to).
# Each binary keeps its own PoCL cache, warmed by one untimed run: their caches' manifests
# differ, and a build reading the other's would pay for checking it.
# Prints and writes bench/results/table_vs_baseline.txt (bench/results.sh: OUT=FILE elsewhere;
# -haswell.txt under POCL_LLVM_CPU_NAME=haswell), headed by commit, machine, date and CPU target.
# Usage: bench/table_vs_baseline.sh [rounds] [baseline commit] [build dir]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
rounds=${1:-3}
base=${2:-01e7a02}
build=${3:-build}
new=$build/depthprec
[ -x "$new" ] || { echo "no $new: build first (scripts/build.sh)" >&2; exit 2; }
work=$(mktemp -d)
result=$(result_path table_vs_baseline txt)
cleanup() {
  git worktree remove --force "$work/src" > /dev/null 2>&1 || true
  rm -rf "$work" "$result.tmp"
}
trap cleanup EXIT
git worktree add --detach "$work/src" "$base" > /dev/null 2>&1
cmake -S "$work/src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$work/build" -j "$(nproc)" --target depthprec > /dev/null
old=$work/build/depthprec

run() {  # name, binary, then table options: table_run with the binary's own PoCL cache
  POCL_CACHE_DIR="$work/pocl-$1" table_run "$work" "$@"
}

measure() {
  result_header "bench/table_vs_baseline.sh $rounds $base $build: the default table (table" \
    "--format-out csv --no-timing) against $base's table --set sampling=paper, alternately; wall" \
    "and peak RSS (GNU time)"
  # warm-up: each binary compiles its kernels into its own cache
  run baseline_paper "$old" --set sampling=paper
  run baseline_worst_case "$old"
  run default "$new"
  : > "$work/runs"
  for ((i = 0; i < rounds; i++)); do
    run baseline_paper "$old" --set sampling=paper
    run default "$new"
  done
  runs_summary "$work" baseline_paper default
  awk -v d="$(runs_median "$work" default)" -v p="$(runs_median "$work" baseline_paper)" -v b="$base" \
    'BEGIN { printf "default table / %s paper table, wall medians: %.2fx\n", b, d / p }'
  python3 bench/table_ratios.py "$work/baseline_worst_case.csv" "$work/default.csv" \
    "default table's mts / $base's worst case"
}
mkdir -p "$(dirname "$result")"
measure | tee "$result.tmp"
mv "$result.tmp" "$result"
