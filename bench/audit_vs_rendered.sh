#!/usr/bin/env bash
# The audit against the system's OpenGL (llvmpipe without a GPU) on every scene of data/audit/:
# per scene, set-up and profile, one view (the file's camera) at 240x136, the emulated fighting
# and at-risk pixels, the rendered fighting pixels, every pixel whose fight verdicts differ sorted
# by why, and of those the rendered fights the emulation did not call fights (missed_*: at risk,
# on a coverage edge, or unexplained, which the audit's guarantee says is zero) (docs/audit.md "Checked against the real thing"). Writes
# bench/results/audit_vs_rendered.csv (override with OUT=...), headed by the commit, the machine and
# the renderer. Not a test: tests/audit/ holds the audit to the same sorting.
# Usage: bench/audit_vs_rendered.sh
set -euo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-bench/results/audit_vs_rendered.csv}"
mkdir -p "$(dirname "$out")"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
setups=("standard unorm24" "standard float32" "reversed float32" "log_fragment float32")
{
  echo "# commit $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- host kernels interface || echo '+changes'), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(date -u +%F)"
  echo "# build/depthprec audit data/audit/FILE -t T -f F --profile P --size 240x136 --frames 1 --source rendered --no-fixes"
  echo "scene,technique,format,profile,emulated_fights,at_risk,rendered_fights,differ_seam,differ_coplanar,differ_tie,differ_at_risk,differ_edge,differ_other,missed_at_risk,missed_edge,missed_unexplained,renderer"
  for scene in data/audit/*.gltf data/audit/*.glb; do
    for setup in "${setups[@]}"; do
      read -r t f <<<"$setup"
      for p in ideal llvmpipe; do
        build/depthprec audit "$scene" -t "$t" -f "$f" --profile "$p" --size 240x136 --frames 1 \
          --source rendered --no-fixes --format-out json -q -o "$tmp/a.json"
        python3 - "$tmp/a.json" "$(basename "$scene")" "$t" "$f" "$p" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
s = j['setups'][0]
r = s['rendered']
d = r['fights_differ']
m = r['fights_missed']  # rendered fights the emulation did not call fights
print(','.join(str(v) for v in [sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5],
      s['fighting_pixels'], s['at_risk_pixels'], r['fighting_pixels'], d['seam'], d['coplanar'],
      d['tie'], d['at_risk'], d['edge'], d['other'], m['at_risk'], m['edge'],
      m['tie'] + m['other'], '"' + r['renderer'] + '"']))
PY
      done
    done
  done
} >"$out"
echo "wrote $out"
