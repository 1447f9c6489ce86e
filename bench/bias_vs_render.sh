#!/usr/bin/env bash
# depthprec bias emulated (with llvmpipe's r for unorm buffers, --r-unorm double_step) against
# the same searches rendered with glPolygonOffset on the system's OpenGL, row by row: the
# constant units, the slope factor alone and the units beside factor 1, and how many agree.
# Extra arguments go to both runs (default: the pairs and distances of docs/bias.md). Prints and
# writes to bench/results/bias_vs_render.txt (bench/results.sh: OUT=FILE elsewhere; -haswell.txt
# under POCL_LLVM_CPU_NAME=haswell), headed by commit, machine, date and CPU target.
# Usage: bench/bias_vs_render.sh [depthprec bias options]...
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=build/depthprec
args=("$@")
[ ${#args[@]} -gt 0 ] ||
  args=(-t standard,reversed,infinite,reversed_infinite,log_vertex,layered
        -f unorm16,unorm24,float32 --distances 2,100,1e4,1e6)
out=$(mktemp -d)
result=$(result_path bias_vs_render txt)
trap 'rm -rf "$out" "$result.tmp"' EXIT

measure() {
  result_header "bench/bias_vs_render.sh: depthprec bias ${args[*]} --r-unorm double_step, then" \
    "the same with --source rendered; wall time and peak RSS (GNU time) of each"
  /usr/bin/time -f '%e %M' -o "$out/e.time" \
    "$bin" bias "${args[@]}" --r-unorm double_step -q --no-timing --format-out json -o "$out/e.json"
  /usr/bin/time -f '%e %M' -o "$out/r.time" \
    "$bin" bias "${args[@]}" --source rendered -q --no-timing --format-out json -o "$out/r.json"
  python3 - "$out/e.json" "$out/r.json" "$out/e.time" "$out/r.time" <<'PY'
import json, sys
e, r = (json.load(open(p)) for p in sys.argv[1:3])
(te, ke), (tr, kr) = (open(p).read().split() for p in sys.argv[3:5])
print(f"emulated {float(te):.1f} s, {int(ke) // 1024} MB; rendered {float(tr):.1f} s, "
      f"{int(kr) // 1024} MB on {r.get('renderer', '?')}\n")
print("| pair | z | units e / r | factor e / r | set units e / r |")
print("|---|---|---|---|---|")
fields = ("units", "factor", "set_units")
same = {f: 0 for f in fields}
diff_units = []
rows = 0
for er, rr in zip(e["records"], r["records"]):
    for a, b in zip(er["rows"], rr["rows"]):
        rows += 1
        cells = []
        for f in fields:
            va, vb = a.get(f), b.get(f)
            same[f] += va == vb
            cells.append(f"{va} / {vb}" if va != vb else f"{va}")
        if a.get("units") is not None and b.get("units") is not None:
            diff_units.append(abs(b["units"]) - abs(a["units"]))
        pair = f"{a['technique']}/{a['format']}"
        print(f"| {pair} | {a['z']:g} | " + " | ".join(cells) + " |")
print()
for f in fields:
    print(f"{f}: identical in {same[f]} of {rows} rows")
more = sum(1 for d in diff_units if d > 0)
less = sum(1 for d in diff_units if d < 0)
print(f"units, both resolved: rendered needs more in {more}, fewer in {less}, "
      f"largest difference {max(diff_units, key=abs) if diff_units else 0:g}")
PY
}
mkdir -p "$(dirname "$result")"
measure | tee "$result.tmp"
mv "$result.tmp" "$result"
