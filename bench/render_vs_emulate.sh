#!/usr/bin/env bash
# The same MTS measurement emulated and rendered, one after the other in one run: wall time and
# peak RSS (GNU time) of `depthprec mts` and `depthprec render` for each pair given (default:
# standard/unorm24 and reversed/float32 over the default scene's 30 distances, 100 frames) and the
# ratio of the wall times, each command with its defaults (mts splits a lone pair's distances
# between its two jobs; llvmpipe renders on every core). Both rows must agree on the scene; the
# emulator's PoCL cache is warmed first so compilation is not counted. Prints and writes to
# bench/results/render_vs_emulate.txt (bench/results.sh: OUT=FILE elsewhere; -haswell.txt under
# POCL_LLVM_CPU_NAME=haswell), headed by commit, machine, date and CPU target.
# Usage: bench/render_vs_emulate.sh [technique format]...
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=build/depthprec
pairs=("$@")
[ ${#pairs[@]} -gt 0 ] || pairs=(standard unorm24 reversed float32)
out=$(result_path render_vs_emulate txt)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp" "$out.tmp"' EXIT

measure() {
  result_header "bench/render_vs_emulate.sh ${pairs[*]}: depthprec mts -t T -f F -q, then" \
    "depthprec render -t T -f F -q (the renderer: depthprec devices, or render's JSON header)"
  printf '%-28s %12s %12s %8s %14s %14s\n' pair emulated_s rendered_s ratio emulated_MB rendered_MB
  for ((i = 0; i < ${#pairs[@]}; i += 2)); do
    local t=${pairs[i]} f=${pairs[i + 1]}
    "$bin" mts -t "$t" -f "$f" --distances 2 --frames 1 -q > /dev/null  # warm PoCL's cache
    /usr/bin/time -f '%e %M' -o "$tmp/e" "$bin" mts -t "$t" -f "$f" -q > /dev/null
    /usr/bin/time -f '%e %M' -o "$tmp/r" "$bin" render -t "$t" -f "$f" -q > /dev/null
    read -r es ekb < "$tmp/e"
    read -r rs rkb < "$tmp/r"
    awk -v p="$t/$f" -v e="$es" -v r="$rs" -v em="$ekb" -v rmb="$rkb" \
      'BEGIN { printf "%-28s %12.2f %12.2f %7.1fx %14d %14d\n", p, e, r, r / e, em / 1024, rmb / 1024 }'
  done
}
mkdir -p "$(dirname "$out")"
measure | tee "$out.tmp"
mv "$out.tmp" "$out"
