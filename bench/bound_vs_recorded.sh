#!/usr/bin/env bash
# Today's guaranteed MTS against the renderings on record: the rendered MTS of every row of
# data/validation.json in bench/results/bound_vs_rendered.txt (llvmpipe) and
# bound_vs_rendered-softpipe.txt (softpipe), which took hours to render, held against the
# mts_bound this build gives the same rows (depthprec mts data/validation.json; the bound does not
# depend on the sampling). For a change of the bound alone, where rendering again would give the
# same rendered MTS. Prints and writes bench/results/bound_vs_recorded.txt (bench/results.sh),
# headed by commit, machine, date and CPU target. About a minute on 2 cores.
# Usage: bench/bound_vs_recorded.sh
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${DEPTHPREC:-build/depthprec}
out=$(mktemp -d)
result=$(result_path bound_vs_recorded txt)
trap 'rm -rf "$out" "$result.tmp"' EXIT
measure() {
  result_header "bench/bound_vs_recorded.sh: the rendered MTS recorded in" \
    "bench/results/bound_vs_rendered.txt and bound_vs_rendered-softpipe.txt against the mts_bound" \
    "of depthprec mts data/validation.json --set sampling=paper (rows recorded with a bound only)"
  "$bin" mts data/validation.json --set sampling=paper -q --no-timing --format-out json \
    -o "$out/bounds.json"
  python3 bench/bound_vs_rendered.py --bounds "$out/bounds.json" \
    llvmpipe=bench/results/bound_vs_rendered.txt softpipe=bench/results/bound_vs_rendered-softpipe.txt
}
measure | tee "$result.tmp"
mv "$result.tmp" "$result"
