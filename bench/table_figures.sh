#!/usr/bin/env bash
# The figures of the speed issue in one run: the default table with PoCL's kernel cache cold
# (an empty POCL_CACHE_DIR: what a first run on a machine pays) and warm, each with its wall time,
# peak RSS and fragment pairs per second; then standard/unorm24 over the default distances
# emulated and rendered on this machine's OpenGL, side by side (bench/render_vs_emulate.sh).
# The cold and warm tables must be the same but for their measured times.
# Usage: bench/table_figures.sh [build dir]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
bin=$build/depthprec
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# One table run: wall seconds and peak RSS from GNU time, pairs/s from the table's own footer.
table() {  # name, then environment assignments
  local name=$1
  shift
  env "$@" /usr/bin/time -f '%e %M' -o "$out/$name.time" \
    "$bin" table --format-out markdown -o "$out/$name.md" -q
  read -r secs kb < "$out/$name.time"
  rate=$(sed -n 's/.* \([0-9.e+]*\) fragment pairs\/s.*/\1/p' "$out/$name.md")
  printf '%-22s %9.2f s %9.0f MB %14s pairs/s\n' "$name" "$secs" "$((kb / 1024))" "${rate:-?}"
}

printf '%-22s %11s %12s %22s\n' "default table" "wall" "peak RSS" "rate"
cold_cache=$(mktemp -d)
table cold POCL_CACHE_DIR="$cold_cache"
table warm POCL_CACHE_DIR="$cold_cache"
rm -rf "$cold_cache"
# The same table either way (the footer's measured times aside).
cmp -s <(grep -v 'wall time' "$out/cold.md") <(grep -v 'wall time' "$out/warm.md") ||
  { echo "cold and warm tables differ" >&2; exit 1; }
echo
bench/render_vs_emulate.sh standard unorm24
