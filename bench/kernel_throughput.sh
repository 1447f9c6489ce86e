#!/usr/bin/env bash
# The MTS kernel's throughput per (technique, format) and regime, and the scalar host reference's
# beside it: build/bench/mts_throughput (bench/mts_throughput.cpp; regimes in host/mts/mts_timing.h)
# with the arguments given (default: the four techniques and two formats of docs/performance.md, a
# 200 x 200 kernel, the fastest of 5). Prints and writes to bench/results/kernel_throughput.txt
# (bench/results.sh: OUT=FILE elsewhere; -haswell.txt under POCL_LLVM_CPU_NAME=haswell), headed by
# commit, machine, date and CPU target.
# Usage: bench/kernel_throughput.sh [techniques formats side repeats [regimes]]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
args=("$@")
[ ${#args[@]} -gt 0 ] || args=(standard,reversed,log_fragment,linear unorm24,float32 200 5)
out=$(result_path kernel_throughput txt)
trap 'rm -f "$out.tmp"' EXIT

measure() {
  result_header "build/bench/mts_throughput ${args[*]}: per regime ns per fragment pair of kernel" \
    "time (the fastest of the repeats); host ref pairs/s: the scalar host reference, one thread"
  build/bench/mts_throughput "${args[@]}"
}
mkdir -p "$(dirname "$out")"
measure | tee "$out.tmp"
mv "$out.tmp" "$out"
