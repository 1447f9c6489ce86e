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

# table_run DIR NAME BINARY [OPTIONS...]  BINARY's table (--format-out csv --no-timing -q, OPTIONS)
#                        into DIR/NAME.csv under GNU time, appending "NAME seconds MB" to DIR/runs
# runs_median DIR NAME   the median wall time of NAME's runs in DIR/runs
# runs_summary DIR NAME...  per NAME: its median and fastest wall time and largest peak RSS
table_run() {
  local dir=$1 name=$2 bin=$3
  shift 3
  /usr/bin/time -f '%e %M' -o "$dir/time" \
    "$bin" table --format-out csv --no-timing -q -o "$dir/$name.csv" "$@"
  read -r secs kb < "$dir/time"
  echo "$name $secs $((kb / 1024))" >> "$dir/runs"
}

runs_median() {
  awk -v n="$2" '$1 == n { print $2 }' "$1/runs" | sort -g |
    awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

runs_summary() {
  local dir=$1 name
  shift
  for name in "$@"; do
    awk -v n="$name" '$1 == n { print $2, $3 }' "$dir/runs" | sort -g | awk -v n="$name" '
      { t[NR] = $1; if ($2 > m) m = $2 }
      END { printf "%-15s wall median %.2f s (of %d runs, fastest %.2f s), peak RSS %d MB\n", n,
            (NR % 2) ? t[(NR + 1) / 2] : (t[NR / 2] + t[NR / 2 + 1]) / 2, NR, t[1], m }'
  done
}
