#!/usr/bin/env bash
# The guaranteed MTS against rendering: every row of data/validation.json rendered on the system's
# OpenGL, on llvmpipe and on softpipe, and each rendered row's MTS held against its
# mts_bound (the bound does not depend on the sampling; the rendering samples the paper's frames
# unless extra arguments say otherwise). Prints and writes bench/results/bound_vs_rendered.txt
# (bench/results.sh), headed by commit, machine, date and CPU target.
# Usage: bench/bound_vs_rendered.sh [depthprec render options]...
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${DEPTHPREC:-build/depthprec}  # another build (a copy) may be named
args=("$@")
[ ${#args[@]} -gt 0 ] || args=(--set sampling=paper)
out=$(mktemp -d)
result=$(result_path bound_vs_rendered txt)
trap 'rm -rf "$out" "$result.tmp"' EXIT

measure() {
  result_header "bench/bound_vs_rendered.sh: depthprec render data/validation.json ${args[*]}" \
    "on llvmpipe, then on softpipe (GALLIUM_DRIVER); rendered mts against mts_bound"
  /usr/bin/time -f '%e' -o "$out/l.time" \
    "$bin" render data/validation.json "${args[@]}" -q --no-timing --format-out json \
    -o "$out/llvmpipe.json"
  GALLIUM_DRIVER=softpipe MESA_GL_VERSION_OVERRIDE=4.5 MESA_GLSL_VERSION_OVERRIDE=450 \
    /usr/bin/time -f '%e' -o "$out/s.time" \
    "$bin" render data/validation.json "${args[@]}" -q --no-timing \
    --format-out json -o "$out/softpipe.json"
  echo "rendering took $(cat "$out/l.time") s (llvmpipe) and $(cat "$out/s.time") s (softpipe)"
  echo
  python3 bench/bound_vs_rendered.py llvmpipe="$out/llvmpipe.json" softpipe="$out/softpipe.json"
}

measure | tee "$result.tmp"
mv "$result.tmp" "$result"
