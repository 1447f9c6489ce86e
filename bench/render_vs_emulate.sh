#!/usr/bin/env bash
# The same MTS measurement emulated and rendered, one after the other in one run: wall time of
# `depthprec mts` and `depthprec render` for each pair given (default: standard/unorm24 over the
# default scene's 30 distances, 100 frames) and the ratio, each command with its defaults (mts
# splits a lone pair's distances between its two jobs; llvmpipe renders on every core). Both rows
# must agree on the scene; the emulator's PoCL cache is warmed first so compilation is not
# counted.
# Usage: bench/render_vs_emulate.sh [technique format]...
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/depthprec
pairs=("$@")
[ ${#pairs[@]} -gt 0 ] || pairs=(standard unorm24)
printf '%-28s %12s %12s %8s\n' pair emulated_s rendered_s ratio
for ((i = 0; i < ${#pairs[@]}; i += 2)); do
  t=${pairs[i]} f=${pairs[i + 1]}
  "$bin" mts -t "$t" -f "$f" --distances 2 --frames 1 -q > /dev/null  # warm PoCL's cache
  s0=$(date +%s.%N)
  "$bin" mts -t "$t" -f "$f" -q > /dev/null
  s1=$(date +%s.%N)
  "$bin" render -t "$t" -f "$f" -q > /dev/null
  s2=$(date +%s.%N)
  awk -v p="$t/$f" -v a="$s0" -v b="$s1" -v c="$s2" \
    'BEGIN { e = b - a; r = c - b; printf "%-28s %12.2f %12.2f %7.1fx\n", p, e, r, r / e }'
done
