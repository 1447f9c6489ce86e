#!/usr/bin/env bash
# The figures of the speed issue in one run: the default table compiling every kernel, as a first
# run after building meets it (PoCL's cache and the user's program binaries empty, the build's
# kernel-cache/ there), and warm, each with its wall time, peak RSS and fragment pairs per second;
# then the same warm table under the llvmpipe profile and its ratio to the ideal one (at most 2x
# is the aim); then standard/unorm24 over the default distances emulated and rendered on this machine's
# OpenGL, side by side (bench/render_vs_emulate.sh). The tables must be the same but for their
# measured times. Prints and writes to bench/results/table_figures.txt (bench/results.sh: OUT=FILE
# elsewhere; -haswell.txt under POCL_LLVM_CPU_NAME=haswell), headed by commit, machine, date and CPU
# target.
# Usage: bench/table_figures.sh [build dir]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
build=${1:-build}
bin=$build/depthprec
out=$(mktemp -d)
result=$(result_path table_figures txt)
trap 'rm -rf "$out" "$result.tmp"' EXIT

# One table run: wall seconds and peak RSS from GNU time, pairs/s from the table's own footer.
table_args=()  # more table options
table() {  # name, then environment assignments
  local name=$1
  shift
  env "$@" /usr/bin/time -f '%e %M' -o "$out/$name.time" \
    "$bin" table --format-out markdown -o "$out/$name.md" -q "${table_args[@]}"
  read -r secs kb < "$out/$name.time"
  rate=$(sed -n 's/.* \([0-9.e+]*\) fragment pairs\/s.*/\1/p' "$out/$name.md")
  printf '%-22s %9.2f s %9.0f MB %14s pairs/s\n' "$name" "$secs" "$((kb / 1024))" "${rate:-?}"
}

measure() {
  result_header "bench/table_figures.sh $build: the default table (table --format-out markdown -q)" \
    "compiled, first run and warm; under --profile llvmpipe; bench/render_vs_emulate.sh standard unorm24"
  printf '%-22s %11s %12s %22s\n' "default table" "wall" "peak RSS" "rate"
  # compiled: nothing kept anywhere (no program binaries, PoCL's cache empty): every kernel compiles.
  # first run: PoCL's cache empty, the build's kernel-cache/ there (what a first run after building
  # or installing meets). warm: PoCL's cache filled by that run.
  pocl=$(mktemp -d) none=$(mktemp -d)
  table compiled POCL_CACHE_DIR="$none" DEPTHPREC_KERNEL_CACHE=off
  table first_run POCL_CACHE_DIR="$pocl" DEPTHPREC_KERNEL_CACHE=
  table warm POCL_CACHE_DIR="$pocl" DEPTHPREC_KERNEL_CACHE=
  table_args=(--profile llvmpipe)
  table llvmpipe_first_run POCL_CACHE_DIR="$pocl" DEPTHPREC_KERNEL_CACHE=
  table llvmpipe_warm POCL_CACHE_DIR="$pocl" DEPTHPREC_KERNEL_CACHE=
  table_args=()
  rm -rf "$pocl" "$none"
  read -r ideal _ < "$out/warm.time"
  read -r profiled _ < "$out/llvmpipe_warm.time"
  awk -v a="$profiled" -v b="$ideal" 'BEGIN { printf "llvmpipe profile / ideal, warm: %.2fx\n", a / b }'
  # The same table every way (the footer's measured times aside).
  for name in first_run warm; do
    cmp -s <(grep -v 'wall time' "$out/compiled.md") <(grep -v 'wall time' "$out/$name.md") ||
      { echo "the $name table differs from the compiled one" >&2; exit 1; }
  done
  echo
  OUT="$out/render_vs_emulate.txt" bench/render_vs_emulate.sh standard unorm24 > /dev/null
  grep -v '^#' "$out/render_vs_emulate.txt"
}
mkdir -p "$(dirname "$result")"
measure | tee "$result.tmp"
mv "$result.tmp" "$result"
