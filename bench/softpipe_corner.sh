#!/usr/bin/env bash
# The orientations bench/bound_scan.sh finds fighting at mts_bound under the softpipe profile
# (bench/results/bound_scan.txt), each as the scene's one frame: the MTS rendered on the
# real softpipe (GALLIUM_DRIVER=softpipe) against the softpipe profile's emulated MTS and the
# bound. Prints and writes bench/results/softpipe_corner.txt (bench/results.sh).
# Usage: bench/softpipe_corner.sh
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=${DEPTHPREC:-build/depthprec}
result=$(result_path softpipe_corner txt)
trap 'rm -f "$result.tmp"' EXIT
# technique format depth_range z and the orientation's rotation_offset (asin(angle / 1 degree))
cases=(
  "standard float32 gl 1.005 [-1.2916101411446705,0.1369202072496045,0.005063566335173581]"
  "reversed float32 zero_to_one 2 [0.150333941980495,-0.3294018736355385,1.358877448785305e-05]"
  "reversed float32 zero_to_one 16384 [-0.679355451094881,0.0016378724238489898,0.0016897698694593715]"
)
measure() {
  result_header "bench/softpipe_corner.sh: render (softpipe) and mts --profile softpipe, one frame" \
    "at each orientation bound_scan found fighting at mts_bound under the softpipe profile"
  echo "pair,z,rendered_softpipe_mts,emulated_softpipe_mts,mts_bound"
  for c in "${cases[@]}"; do
    read -r t f r z offset <<< "$c"
    local common=(-t "$t" -f "$f" --depth-range "$r" --distances "$z" --set frames=1
      --set sampling=paper --set "rotation_offset=$offset" --set bound_model=softpipe
      --no-timing --format-out json -q)
    local rendered emulated
    rendered=$(GALLIUM_DRIVER=softpipe MESA_GL_VERSION_OVERRIDE=4.5 MESA_GLSL_VERSION_OVERRIDE=450 \
      "$bin" render "${common[@]}")
    emulated=$("$bin" mts --profile softpipe "${common[@]}")
    python3 -c '
import json, sys
r, e = (json.loads(a)["rows"][0] for a in sys.argv[1:3])
pair = "/".join((r["technique"], r["format"], r["depth_range"]))
print("%s,%g,%.6g,%.6g,%.6g" % (pair, r["z"], r["mts"], e["mts"], e["mts_bound"]))
' "$rendered" "$emulated"
  done
}
measure | tee "$result.tmp"
mv "$result.tmp" "$result"
