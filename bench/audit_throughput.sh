#!/usr/bin/env bash
# The scene audit's speed and memory on a large scene: a terrain with a road of about 2 N^2
# triangles (scripts/make_audit_scenes.py --terrain N; N = 708 gives 1,005,360 with the road), audited at
# 1920x1080 for one set-up without fixes. Prints the set-up and pixel seconds the JSON reports,
# the command's wall time and peak RSS. Not a test.
# Usage: bench/audit_throughput.sh [N] [technique] [format]
set -euo pipefail
cd "$(dirname "$0")/.."
n="${1:-708}"; t="${2:-reversed}"; f="${3:-float32}"
scene="/tmp/depthprec_terrain_$n.glb"
[ -f "$scene" ] || python3 scripts/make_audit_scenes.py --terrain "$n" "$scene"
/usr/bin/time -f "wall %e s, peak RSS %M kB" build/depthprec audit "$scene" -t "$t" -f "$f" \
  --size 1920x1080 --no-fixes --format-out json -o /tmp/depthprec_audit_bench.json -q
python3 - <<'PY'
import json
j = json.load(open('/tmp/depthprec_audit_bench.json'))
s = j['setups'][0]
print(f"{j['triangles']} triangles, {s['rasterised_triangles']} rasterised, "
      f"set-up {s['setup_seconds']:.2f} s, pixels {s['pixel_seconds']:.2f} s, "
      f"{s['fighting_pixels']} fighting pixels")
PY
