#!/usr/bin/env bash
# How tight the guaranteed MTS is (docs/bound.md, "How tight"): the default table, then the same
# table under the llvmpipe and softpipe profiles (their own worst cases; the bound is the default
# model's in all three), and per pair the medians bench/bound_tightness.py takes. About two
# minutes on 2 cores, most of it softpipe's. Prints and writes bench/results/bound_tightness.txt
# (bench/results.sh), headed by commit, machine, date and CPU target.
# Usage: bench/bound_tightness.sh
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${DEPTHPREC:-build/depthprec}
out=$(mktemp -d)
result=$(result_path bound_tightness txt)
trap 'rm -rf "$out" "$result.tmp"' EXIT

measure() {
  result_header "bench/bound_tightness.sh: depthprec table, then --profile llvmpipe and" \
    "--profile softpipe (the default scene, worst-case sampling); medians per pair"
  "$bin" table --no-timing -q --format-out csv -o "$out/ideal.csv"
  "$bin" table --profile llvmpipe --no-timing -q --format-out csv -o "$out/llvmpipe.csv"
  "$bin" table --profile softpipe --no-timing -q --format-out csv -o "$out/softpipe.csv"
  python3 bench/bound_tightness.py "$out/ideal.csv" "$out/llvmpipe.csv" "$out/softpipe.csv"
}

measure | tee "$result.tmp"
mv "$result.tmp" "$result"
