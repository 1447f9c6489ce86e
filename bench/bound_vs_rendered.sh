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
  python3 - "$out/llvmpipe.json" "$out/softpipe.json" "$out/l.time" "$out/s.time" <<'PY'
import json, statistics, sys
runs = [("llvmpipe", json.load(open(sys.argv[1]))), ("softpipe", json.load(open(sys.argv[2])))]
times = [open(p).read().strip() for p in sys.argv[3:5]]
print(f"rendering took {times[0]} s (llvmpipe) and {times[1]} s (softpipe)\n")
print("| driver | pair | z | rendered mts | mts_bound | bound / rendered |")
print("|---|---|---|---|---|---|")
for name, run in runs:
    below, rows, ratios, unbounded = 0, 0, [], 0
    for r in run["rows"]:
        if r["verdict"] != "resolved":
            continue
        rows += 1
        b = r.get("mts_bound")
        if not isinstance(b, (int, float)):
            unbounded += 1
            continue
        ratios.append(b / r["mts"])
        if b < r["mts"]:
            below += 1
        pair = f"{r['technique']}/{r['format']}/{r['depth_range']}"
        print(f"| {name} | {pair} | {r['z']:g} | {r['mts']:.6g} | {b:.6g} | {b / r['mts']:.3g} |")
    print()
    print(f"{name}: {rows} resolved rows, {len(ratios)} with a finite bound, {unbounded} without; "
          f"bound below the rendered MTS on {below}; bound / rendered: min "
          f"{min(ratios):.3g}, median {statistics.median(ratios):.3g}\n")
PY
}

measure | tee "$result.tmp"
mv "$result.tmp" "$result"
