#!/usr/bin/env bash
# The guaranteed MTS against a dense scan: build/bench/bound_scan N (default 10^5 orientations
# per row and profile, a dozen rows of the default scene, each profile under its own bound
# model). Prints and writes bench/results/bound_scan.txt (bench/results.sh), headed by commit,
# machine, date and CPU target.
# Usage: bench/bound_scan.sh [N]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${BOUND_SCAN:-build/bench/bound_scan}  # another build (a copy) may be named
n=${1:-100000}
result=$(result_path bound_scan txt)
trap 'rm -f "$result.tmp"' EXIT
{
  result_header "bench/bound_scan.sh $n: build/bench/bound_scan $n (wall time at the end)"
  start=$(date +%s)
  "$bin" "$n"
  echo "wall time $(($(date +%s) - start)) s"
} | tee "$result.tmp"
mv "$result.tmp" "$result"
