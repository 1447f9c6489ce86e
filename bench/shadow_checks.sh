#!/usr/bin/env bash
# `depthprec shadow` checked three ways on a matrix of set-ups (formats, filters, reversed, a far
# world position, a high sun): per cascade the proven constant, slope factor and normal offset,
# the emulation's witnessed share of each (kernels/shadow.cl), acne in the rendered shadow pass on
# the system's OpenGL at the bound and at 90 % of it, and the gap the constant costs (formula,
# ray cast, rendered), with each run's wall time. Prints and writes bench/results/shadow_checks.txt
# (bench/results.sh: OUT=FILE elsewhere). About 40 seconds on 2 cores.
# Usage: bench/shadow_checks.sh
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${DEPTHPREC:-build/depthprec}
tmp=$(mktemp -d)
result=$(result_path shadow_checks txt)
trap 'rm -rf "$tmp" "$result.tmp"' EXIT

setups=(
  ""
  "--format unorm16 --filter nearest"
  "--format unorm24 --filter pcf2x2 --api d3d"
  "--format float32 --reversed --filter tent5"
  "--format unorm16 --filter pcf5 --slope-max 85 --resolution 512"
  "--format unorm24 --filter nearest --world-position 20000,0,15000"
  "--light-elevation 80 --slope-max 45"
  "--light spot --distances 2,10,45 --light-far 50 --filter tent5"
  "--light spot --distances 2,10,45 --light-far 50 --filter tent5 --reversed --world-position 5000,0,3000"
)

measure() {
  result_header "bench/shadow_checks.sh: depthprec shadow --source rendered SETUP --format-out json" \
    "(four cascades split at 10/40/150/600 m, 2048^2, float32, pcf3, slopes to 80 deg unless SETUP says)"
  echo "renderer: $("$bin" shadow --source rendered --splits 10 --planes 16 -q --format-out json | python3 -c 'import json,sys; print(json.load(sys.stdin)["renderer"])')"
  echo
  echo "| set-up | cascade (spot: distance m) | texel m | constant r | slope | normal texels | witnessed c/s/n | rendered acne at bound | rendered acne at 90 % c/s/n | gap m | ray cast m | rendered m | wall s |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  for setup in "${setups[@]}"; do
    # shellcheck disable=SC2086
    /usr/bin/time -f '%e' -o "$tmp/time" "$bin" shadow --source rendered $setup -q \
      --format-out json -o "$tmp/out.json"
    python3 - "${setup:-(defaults)}" "$tmp" <<'PY'
import json, sys
setup, tmp = sys.argv[1], sys.argv[2]
d = json.load(open(f"{tmp}/out.json"))
wall = float(open(f"{tmp}/time").read())
for c in d["cascades"]:
    b, w, r = c["bound"], c["witnessed"], c["rendered"]
    share = lambda k, bk: f"{100 * w[k] / b[bk]:.0f}%" if b.get(bk) and w.get(k) is not None else "-"
    g = r.get("gap", {"formula": float("nan"), "raycast": float("nan"), "rendered": float("nan")})
    below = "/".join(str(r[k].get("acne_at_90_percent", "-")) for k in ("constant", "slope", "normal"))
    at_bound = sum(r[k].get("acne_at_bound", 0) for k in ("constant", "slope", "normal"))
    print(f"| {setup} | {c.get('distance', c['cascade'])} | {c['texel']:.4g} | {b['constant_units']:.4g} | "
          f"{b['slope_factor']:.4g} | {b['normal_texels'] if b['normal_texels'] is None else format(b['normal_texels'], '.4g')} | "
          f"{share('constant_units', 'constant_units')}/{share('slope_factor', 'slope_factor')}/"
          f"{share('normal_metres', 'normal_metres')} | {at_bound} | {below} | {g['formula']:.4g} | "
          f"{g['raycast']:.4g} | {g['rendered']:.4g} | {wall:.2f} |")
PY
  done
}

measure | tee "$result.tmp"
mv "$result.tmp" "$result"
