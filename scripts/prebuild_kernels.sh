#!/usr/bin/env bash
# Compiles the default scene's kernel variants into a program binary cache (the build's
# kernel_cache target, CMakeLists.txt): usage prebuild_kernels.sh DEPTHPREC CACHE_DIR FORMAT...
# One tiny default table per storage format, all at once: PoCL compiles one kernel at a time per
# process, and the formats' variants are disjoint, so each process compiles its own share on its
# own core. Without an OpenCL device nothing is compiled and the first run does it instead.
set -uo pipefail
exe=$1 dir=$2
shift 2
rm -rf "$dir"
pids=()
for format in "$@"; do
  DEPTHPREC_KERNEL_CACHE=$dir "$exe" table -f "$format" --kernel 16x16 --frames 1 \
    --distances 2,1e6 --no-timing -q --format-out csv > /dev/null &
  pids+=($!)
done
failed=0
for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
if [ "$failed" != 0 ]; then
  echo "depthprec: kernels not compiled at build time (no OpenCL device?): the first run compiles them"
fi
exit 0
