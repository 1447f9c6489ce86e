#!/usr/bin/env bash
# The API envelopes' bounds against every emulated implementation (docs/spec.md 2, "Envelopes";
# docs/bound.md): the default table under the ideal, llvmpipe and softpipe
# profiles and under each envelope's adversary (d3d11, vulkan_min), whose rows carry the
# envelope's own bound. bench/envelope_bounds.py checks each envelope's bound against every
# profile's worst case row by row and gives, per technique, the median of its bound over the
# default table's (the default model, binary32). About three minutes on 2 cores. Prints and writes
# bench/results/envelope_bounds.txt (bench/results.sh), headed by commit, machine, date and CPU
# target.
# Usage: bench/envelope_bounds.sh
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${DEPTHPREC:-build/depthprec}
out=$(mktemp -d)
result=$(result_path envelope_bounds txt)
trap 'rm -rf "$out" "$result.tmp"' EXIT

measure() {
  result_header "bench/envelope_bounds.sh: depthprec table --profile P for P in ideal, llvmpipe," \
    "softpipe, d3d11, vulkan_min (the default scene, worst-case sampling)"
  for p in ideal llvmpipe softpipe d3d11 vulkan_min; do
    "$bin" table --profile "$p" --no-timing -q --format-out json -o "$out/$p.json"
  done
  python3 bench/envelope_bounds.py "$out"/{ideal,llvmpipe,softpipe,d3d11,vulkan_min}.json
}

measure | tee "$result.tmp"
mv "$result.tmp" "$result"
