# Sourced by the bench scripts that keep their figures in bench/results/ (docs/performance.md).
#
# result_path NAME EXT   bench/results/NAME.EXT, or NAME-$POCL_LLVM_CPU_NAME.EXT when PoCL is told
#                        to compile for another CPU (POCL_LLVM_CPU_NAME=haswell: AVX2 code on an
#                        AVX-512 machine), so the two targets' figures stand side by side;
#                        $OUT overrides it.
# result_commit          the commit checked out, +changes when host/, kernels/, interface/ or
#                        formats/ differ from it (the build measured is the caller's to match)
# result_machine         the CPU model (/proc/cpuinfo), cores and memory
# result_target          the CPU PoCL compiles the kernels for: POCL_LLVM_CPU_NAME's, or native
#                        with the widest vector extension the CPU has
# result_header TEXT     the lines that head a result file: TEXT (what was run), then commit,
#                        machine, date (UTC) and CPU target
#
# A script writes FILE.tmp as it measures (tee) and renames it to FILE once the run has succeeded,
# so a failed or interrupted run leaves the last complete result in place.

result_path() {
  local name=$1 ext=$2
  if [ -n "${OUT:-}" ]; then
    echo "$OUT"
  else
    echo "bench/results/$name${POCL_LLVM_CPU_NAME:+-$POCL_LLVM_CPU_NAME}.$ext"
  fi
}

result_commit() {
  local c
  c=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
  git diff --quiet HEAD -- host kernels interface formats 2>/dev/null || c="$c+changes"
  echo "$c"
}

result_machine() {
  local cpu mem
  cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')
  mem=$(awk '/^MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo)
  echo "${cpu:-unknown CPU}, $(nproc) cores, $mem"
}

result_target() {
  if [ -n "${POCL_LLVM_CPU_NAME:-}" ]; then
    echo "$POCL_LLVM_CPU_NAME (POCL_LLVM_CPU_NAME)"
  elif grep -qw avx512f /proc/cpuinfo; then
    echo "native (AVX-512)"
  elif grep -qw avx2 /proc/cpuinfo; then
    echo "native (AVX2)"
  else
    echo "native"
  fi
}

result_header() {
  echo "# $*"
  echo "# commit $(result_commit); $(result_machine); $(date -u +%F); CPU target $(result_target)"
}
