#!/bin/sh
# The figures of the speed issue side by side: the MTS kernel's fragment pairs per second for
# standard/unorm24 at the MTS (both cores, PoCL), the scalar host reference's (one thread, every
# pixel), and the default table's wall time (warm kernel cache: run it once before).
# Usage: bench/side_by_side.sh [build dir]
set -eu
build=${1:-build}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/bench/mts_throughput" standard unorm24 200 10 at_mts > "$out/bench.txt"
"$build/depthprec" table --format-out markdown -o "$out/table.md" > /dev/null
awk 'NR == 2 { kernel = $6; host = $10 }
     END { printf "MTS kernel, standard/unorm24 at the MTS: %s fragment pairs/s\n", kernel
           printf "scalar host reference, same pair:       %s fragment pairs/s\n", host }' "$out/bench.txt"
sed -n 's/.*wall time: \([0-9.]* s\).*/default table (depthprec table):         \1 wall time/p' "$out/table.md"
