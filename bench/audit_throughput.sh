#!/usr/bin/env bash
# The scene audit's speed and memory on a large scene: a terrain with a road of about 2 N^2
# triangles (scripts/make_audit_scenes.py --terrain N; N = 708 gives 1,005,360 with the road),
# audited at 1920x1080 for one set-up, once without fixes (the set-up and pixel seconds the JSON
# reports, the command's wall time and peak RSS) and once with them (wall time and peak RSS).
# Prints and writes to bench/results/audit_throughput.txt (bench/results.sh: OUT=FILE elsewhere;
# -haswell.txt under POCL_LLVM_CPU_NAME=haswell), headed by commit, machine, date and CPU target.
# Not a test.
# Usage: bench/audit_throughput.sh [N] [technique] [format]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
n="${1:-708}"; t="${2:-reversed}"; f="${3:-float32}"
scene="/tmp/depthprec_terrain_$n.glb"
[ -f "$scene" ] || python3 scripts/make_audit_scenes.py --terrain "$n" "$scene" >&2
tmp=$(mktemp -d)
out=$(result_path audit_throughput txt)
trap 'rm -rf "$tmp" "$out.tmp"' EXIT

measure() {
  result_header "bench/audit_throughput.sh $n $t $f: build/depthprec audit" \
    "/tmp/depthprec_terrain_$n.glb -t $t -f $f --size 1920x1080, without and with fixes; GNU time"
  /usr/bin/time -f '%e %M' -o "$tmp/time" build/depthprec audit "$scene" -t "$t" -f "$f" \
    --size 1920x1080 --no-fixes --format-out json -o "$tmp/audit.json" -q
  read -r secs kb < "$tmp/time"
  python3 - "$tmp/audit.json" "$secs" "$kb" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
s = j['setups'][0]
print(f"without fixes: {j['triangles']} triangles, {s['rasterised_triangles']} rasterised, "
      f"set-up {s['setup_seconds']:.2f} s, pixels {s['pixel_seconds']:.2f} s, "
      f"{s['fighting_pixels']} fighting pixels; wall {float(sys.argv[2]):.2f} s, "
      f"peak RSS {int(sys.argv[3]) // 1024} MB")
PY
  /usr/bin/time -f '%e %M' -o "$tmp/time" build/depthprec audit "$scene" -t "$t" -f "$f" \
    --size 1920x1080 --no-timing -q -o "$tmp/fixes.txt"
  read -r secs kb < "$tmp/time"
  echo "with fixes: wall $secs s, peak RSS $((kb / 1024)) MB"
}
mkdir -p "$(dirname "$out")"
measure | tee "$out.tmp"
mv "$out.tmp" "$out"
