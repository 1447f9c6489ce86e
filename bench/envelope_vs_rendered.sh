#!/usr/bin/env bash
# The API envelopes' guaranteed MTS against real rasterizers (docs/spec.md 2, "Envelopes"): each
# envelope's mts_bound for every row of data/validation.json (the bound needs no rendering, about
# 15 s an envelope) held against the MTS bench/bound_vs_rendered.sh rendered on llvmpipe and
# softpipe (its result tables, bench/results/bound_vs_rendered*.txt). Prints and writes
# bench/results/envelope_vs_rendered.txt (bench/results.sh), headed by commit, machine, date and
# CPU target.
# Usage: bench/envelope_vs_rendered.sh
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${DEPTHPREC:-build/depthprec}
out=$(mktemp -d)
result=$(result_path envelope_vs_rendered txt)
trap 'rm -rf "$out" "$result.tmp"' EXIT

measure() {
  result_header "bench/envelope_vs_rendered.sh: depthprec mts data/validation.json" \
    "--set sampling=paper --set bound_model=E for E in d3d11, vulkan_min, against the rendered" \
    "MTS of bench/results/bound_vs_rendered.txt (llvmpipe) and bound_vs_rendered-softpipe.txt"
  for e in d3d11 vulkan_min; do
    "$bin" mts data/validation.json --set sampling=paper --set bound_model="$e" -q --no-timing \
      --format-out json -o "$out/$e.json"
  done
  python3 bench/envelope_vs_rendered.py bench/results/bound_vs_rendered.txt \
    bench/results/bound_vs_rendered-softpipe.txt -- d3d11="$out/d3d11.json" \
    vulkan_min="$out/vulkan_min.json"
}

measure | tee "$result.tmp"
mv "$result.tmp" "$result"
