#!/bin/sh
# Instructions per timed repeat of mts_throughput's at_mts probes, per kernel, counted by callgrind:
# exact and repeatable, where this VM's timings drift by +-15 % (docs/performance.md).
# PoCL under valgrind compiles its kernels for the CPU valgrind reports (AVX2, no AVX-512), so the
# counts are of AVX2 code. The search that places the probes and the plane-A cache filling run
# before the timed repeats; they cancel in the difference of a run with 3 repeats and one with 1.
# Usage: bench/instructions.sh [mts_throughput binary] [technique] [format]   (needs valgrind)
set -eu
bin=${1:-build/bench/mts_throughput}
tech=${2:-standard}
fmt=${3:-unorm24}
command -v valgrind >/dev/null || { echo "bench/instructions.sh: valgrind is not installed" >&2; exit 2; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for n in 1 3; do
  valgrind --tool=callgrind --callgrind-out-file="$dir/$n.out" "$bin" "$tech" "$fmt" 200 "$n" at_mts \
    >/dev/null 2>&1
  callgrind_annotate "$dir/$n.out" 2>/dev/null |
    awk '$1 ~ /^[0-9,]+$/ && match($0, /:(_pocl_kernel_[a-z_]+_workgroup|row_segments|df_encode[0-9]*) /) {
           name = substr($0, RSTART + 1, RLENGTH - 2); gsub(",", "", $1); print name, $1 }' > "$dir/$n.txt"
done
echo "instructions per timed repeat of mts_throughput $tech $fmt 200 at_mts (16 probes):"
awk 'NR == FNR { one[$1] = $2; next }
     { printf "%-45s %14.0f\n", $1, ($2 - one[$1]) / 2 }' "$dir/1.txt" "$dir/3.txt"
