#!/usr/bin/env bash
# The scene audit's time under the llvmpipe profile against the ideal pipeline's, on every test
# scene of data/audit (their own cameras and set-ups, fixes included: the audit's defaults), one
# run each, alternately; wall time from GNU time and the JSON's per-set-up seconds (set-up,
# pixels, fixes). Prints and writes bench/results/audit_profiles.txt (bench/results.sh: OUT=FILE
# elsewhere; -haswell.txt under POCL_LLVM_CPU_NAME=haswell), headed by commit, machine, date and
# CPU target. About four minutes on 2 cores.
# Usage: bench/audit_profiles.sh
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${DEPTHPREC:-build/depthprec}
tmp=$(mktemp -d)
result=$(result_path audit_profiles txt)
trap 'rm -rf "$tmp" "$result.tmp"' EXIT

measure() {
  result_header "bench/audit_profiles.sh: depthprec audit SCENE --profile ideal|llvmpipe" \
    "--format-out json for each scene of data/audit; wall seconds (GNU time)"
  echo "| scene | ideal s | llvmpipe s | llvmpipe / ideal | ideal fixes s | llvmpipe fixes s |"
  echo "|---|---|---|---|---|---|"
  for scene in data/audit/*.gltf data/audit/*.glb; do
    for p in ideal llvmpipe; do
      /usr/bin/time -f '%e' -o "$tmp/$p.time" "$bin" audit "$scene" --profile "$p" -q \
        --format-out json -o "$tmp/$p.json"
    done
    python3 - "$scene" "$tmp" <<'PY'
import json, sys
scene, tmp = sys.argv[1], sys.argv[2]
wall = {p: float(open(f"{tmp}/{p}.time").read()) for p in ("ideal", "llvmpipe")}
fixes = {p: sum(s.get("fix_seconds", 0) for s in json.load(open(f"{tmp}/{p}.json"))["setups"])
         for p in ("ideal", "llvmpipe")}
print(f"| {scene.split('/')[-1]} | {wall['ideal']:.2f} | {wall['llvmpipe']:.2f} | "
      f"{wall['llvmpipe'] / wall['ideal']:.2f} | {fixes['ideal']:.2f} | {fixes['llvmpipe']:.2f} |")
PY
  done
}

measure | tee "$result.tmp"
mv "$result.tmp" "$result"
