#!/usr/bin/env bash
# depthprec bias emulated (with llvmpipe's r for unorm buffers, --r-unorm double_step) against
# the same searches rendered with glPolygonOffset on the system's OpenGL, row by row: the
# constant units, the slope factor alone and the units beside factor 1, and how many agree.
# Extra arguments go to both runs (default: the pairs and distances of docs/bias.md).
# Usage: bench/bias_vs_render.sh [depthprec bias options]...
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/depthprec
args=("$@")
[ ${#args[@]} -gt 0 ] ||
  args=(-t standard,reversed,infinite,reversed_infinite,log_vertex,layered
        -f unorm16,unorm24,float32 --distances 2,100,1e4,1e6)
out=$(mktemp -d)
s0=$(date +%s.%N)
"$bin" bias "${args[@]}" --r-unorm double_step -q --no-timing --format-out json -o "$out/e.json"
s1=$(date +%s.%N)
"$bin" bias "${args[@]}" --source rendered -q --no-timing --format-out json -o "$out/r.json"
s2=$(date +%s.%N)
python3 - "$out/e.json" "$out/r.json" "$s0" "$s1" "$s2" <<'PY'
import json, sys
e, r = (json.load(open(p)) for p in sys.argv[1:3])
t0, t1, t2 = (float(x) for x in sys.argv[3:6])
print(f"emulated {t1 - t0:.1f} s, rendered {t2 - t1:.1f} s on {r.get('renderer', '?')}\n")
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
rm -rf "$out"
