#!/usr/bin/env bash
# The guaranteed MTS's condition checked densely above the bound (docs/bound.md, "The condition"):
# build/bench/bound_terms --scan over the default scene's pairs at distances from Z_FROM to Z_TO
# (default 1.005 to 4, where plane B passes w = 2 near and the standard projection's clip z
# changes sign), every separation a factor 1.002 apart from mts_bound to 64 times it plus 4 near.
# The search checks only doublings and binade edges above the bound; this looks between them.
# About four minutes on one core. Prints and writes bench/results/bound_check_scan.txt
# (bench/results.sh), headed by commit, machine, date and CPU target; exits 1 if a row fails.
# Usage: bench/bound_check_scan.sh [Z_FROM Z_TO]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
from=${1:-1.005}
to=${2:-4}
result=$(result_path bound_check_scan txt)
trap 'rm -f "$result.tmp"' EXIT
[ -x build/bench/bound_terms ] || { echo "no build/bench/bound_terms: build first" >&2; exit 2; }
{
  result_header "bench/bound_check_scan.sh $from $to: build/bench/bound_terms --scan $from $to" \
    "(the default scene's pairs, distances a factor 1.01 apart)"
  build/bench/bound_terms --scan "$from" "$to"
} | tee "$result.tmp"
mv "$result.tmp" "$result"
