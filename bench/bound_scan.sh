#!/usr/bin/env bash
# The guaranteed MTS against a dense scan: build/bench/bound_scan N (default 10^5 orientations
# per row and profile, a dozen rows of the default scene, each profile under its own bound
# model). Prints and writes bench/results/bound_scan.txt (bench/results.sh), headed by commit,
# machine, date and CPU target.
# A profile named second scans that profile alone, into bound_scan-PROFILE.txt; a row that fights
# is traced to one orientation, its own MTS, and what the kernel without shortcuts and the host
# reference pipeline say of it as the scene's one frame.
# Usage: bench/bound_scan.sh [N [PROFILE]]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${BOUND_SCAN:-build/bench/bound_scan}  # another build (a copy) may be named
n=${1:-100000}
prof=${2:-}
result=$(result_path "bound_scan${prof:+-$prof}" txt)
trap 'rm -f "$result.tmp"' EXIT
{
  result_header "bench/bound_scan.sh $n $prof: build/bench/bound_scan $n $prof (wall time at the end)"
  start=$(date +%s)
  "$bin" "$n" $prof || true
  echo "wall time $(($(date +%s) - start)) s"
} | tee "$result.tmp"
mv "$result.tmp" "$result"
