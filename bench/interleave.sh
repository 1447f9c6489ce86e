#!/bin/sh
# Two builds' mts_throughput, run alternately (A, B, A, B, ...) so the VM's drift falls on both
# alike; prints the median ns/pair per row of each and their ratio.
# Usage: bench/interleave.sh rounds binary_A binary_B [mts_throughput arguments]
#   e.g. bench/interleave.sh 5 /tmp/old_bench build/bench/mts_throughput standard unorm24 200 10 at_mts
set -eu
rounds=$1 a=$2 b=$3
shift 3
out=$(mktemp)
trap 'rm -f "$out"' EXIT
i=0
while [ "$i" -lt "$rounds" ]; do
  "$a" "$@" 2>/dev/null | awk 'NR > 1 { print "A", $1 "/" $2 "/" $3, $7 }' >> "$out"
  "$b" "$@" 2>/dev/null | awk 'NR > 1 { print "B", $1 "/" $2 "/" $3, $7 }' >> "$out"
  i=$((i + 1))
done
# median ns/pair of binary $1 (A or B) on row $2
median() {
  awk -v b="$1" -v k="$2" '$1 == b && $2 == k { print $3 }' "$out" | sort -g |
    awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
for key in $(awk '{ print $2 }' "$out" | sort -u); do
  ma=$(median A "$key")
  mb=$(median B "$key")
  awk -v k="$key" -v a="$ma" -v b="$mb" 'BEGIN { printf "%-32s A %.3f  B %.3f  B/A %.3f\n", k, a, b, b / a }'
done
