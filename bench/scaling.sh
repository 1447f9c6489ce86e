#!/usr/bin/env bash
# How run time grows with kernel pixels, frames, distances and bisection precision, for one pair
# (default reversed/float32/zero_to_one): each knob alone, the others at the default scene's
# values. Prints and writes to bench/results/scaling.txt (bench/results.sh: OUT=FILE elsewhere;
# -haswell.txt under POCL_LLVM_CPU_NAME=haswell), headed by commit, machine, date and CPU target:
# knob, value, fragment pairs, probes, wall seconds. Not a test.
# Usage: bench/scaling.sh [technique] [format] [depth_range]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
t="${1:-reversed}"; f="${2:-float32}"; r="${3:-zero_to_one}"
exe=build/depthprec
all="1.005,2,4,8,16,32,64,128,256,512,1024,2048,4096,8192,16384,32768,65536,131072,262144,524288,1048576,2097152,4194304,8388608,16777216,33554432,67108864,134217728,268435456,536870912"
run() {  # knob value extra-args...
  local knob="$1" value="$2"; shift 2
  "$exe" -q mts -t "$t" -f "$f" --depth-range "$r" --format-out json "$@" > /tmp/depthprec_scaling.json
  python3 - "$knob" "$value" <<'PY'
import json, sys
j = json.load(open('/tmp/depthprec_scaling.json'))
pairs = sum(r['fragment_pairs'] for r in j['rows'])
probes = sum(r['probes'] for r in j['rows'])
print(f"{sys.argv[1]:<10} {sys.argv[2]:>10} {pairs:>14} {probes:>7} {j['wall_seconds']:>9.2f}")
PY
}
measure() {
  result_header "bench/scaling.sh $t $f $r: each knob alone, the others at the default scene's" \
    "values, 16 distances 1.005...32768 except for the distances knob; seconds: the run's wall_seconds"
  printf "%-10s %10s %14s %7s %9s\n" knob value fragment_pairs probes seconds
  d16=$(echo "$all" | cut -d, -f1-16)
  for k in 50 100 200 400; do run kernel "${k}x${k}" --kernel "${k}x${k}" --distances "$d16"; done
  for fr in 10 25 50 100; do run frames "$fr" --frames "$fr" --distances "$d16"; done
  for n in 4 8 16 30; do run distances "$n" --distances "$(echo "$all" | cut -d, -f1-"$n")"; done
  for p in 4 7 10 13; do
    run precision "2^-$p" --set "rel_precision=$(python3 -c "print(2**-$p)")" --distances "$d16"
  done
}
out=$(result_path scaling txt)
trap 'rm -f "$out.tmp"' EXIT
mkdir -p "$(dirname "$out")"
measure | tee "$out.tmp"
mv "$out.tmp" "$out"
