#!/usr/bin/env bash
# The figures of worst-case sampling in one run (docs/mts.md, "The worst case"): the default table
# under sampling=paper and under the default worst_case, alternately (rounds times each, so this
# VM's drift falls on both alike), each run's wall time and peak RSS; then how the worst case's
# rows moved against the paper's and where they stand against the paper's path sampled ten times
# longer (frames=1000, one run: about 90 s on 2 cores). The paper table must equal the one
# `table --set sampling=paper` gave before worst-case sampling existed (checked by the tests'
# byte-identity of CSV output). Prints and writes to bench/results/sampling_figures.txt
# (bench/results.sh: OUT=FILE elsewhere; -haswell.txt under POCL_LLVM_CPU_NAME=haswell), headed by
# commit, machine, date and CPU target.
# Usage: bench/sampling_figures.sh [rounds] [build dir] [more table options]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
rounds=${1:-3}
build=${2:-build}
shift $(($# > 2 ? 2 : $#))
bin=$build/depthprec
out=$(mktemp -d)
result=$(result_path sampling_figures txt)
trap 'rm -rf "$out" "$result.tmp"' EXIT

run() {  # name, then table options
  table_run "$out" "$1" "$bin" "${@:2}"
}

measure() {
  result_header "bench/sampling_figures.sh $rounds $build${*:+ $*}: the default table (table --format-out" \
    "csv --no-timing), worst case and paper's frames alternately; wall and peak RSS (GNU time)"
  for ((i = 0; i < rounds; i++)); do
    run paper --set sampling=paper "$@"
    run worst_case "$@"
  done
  runs_summary "$out" paper worst_case
  awk -v w="$(runs_median "$out" worst_case)" -v p="$(runs_median "$out" paper)" \
    'BEGIN { printf "worst case / paper, wall medians: %.2fx\n", w / p }'
  python3 bench/table_ratios.py "$out/paper.csv" "$out/worst_case.csv" "worst case / paper"
  run paper_1000 --set sampling=paper --set frames=1000 "$@"
  python3 bench/table_ratios.py "$out/paper_1000.csv" "$out/worst_case.csv" \
    "worst case / the paper's path at 1000 frames"
  awk '$1 == "paper_1000" { printf "paper_1000  wall %.2f s, peak RSS %d MB\n", $2, $3 }' "$out/runs"
}
mkdir -p "$(dirname "$result")"
measure "$@" | tee "$result.tmp"
mv "$result.tmp" "$result"
