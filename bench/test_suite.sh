#!/usr/bin/env bash
# The README's test command from a fresh clone of the commit checked out: scripts/test.sh (set-up,
# build, the whole suite with ctest -j), its wall time and peak RSS (GNU time), the tests passed
# and ctest's own time; then scripts/run.sh (the default table) in the same clone. cold: PoCL's
# cache empty, as on a fresh CI machine; warm (default): the user's. Each row goes into
# bench/results/test_suite.csv (bench/results.sh: OUT=FILE elsewhere; test_suite-haswell.csv
# under POCL_LLVM_CPU_NAME=haswell) with its commit, machine, date and CPU target, replacing the
# row of that name. Takes five to seven minutes on 2 cores; run it on an otherwise idle machine.
# Usage: bench/test_suite.sh [warm|cold]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
mode=${1:-warm}
case $mode in warm | cold) ;; *) echo "usage: bench/test_suite.sh [warm|cold]" >&2; exit 2 ;; esac
out=$(result_path test_suite csv)
out=$(realpath -m "$out")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ "$mode" = cold ]; then
  export POCL_CACHE_DIR="$tmp/pocl"
  mkdir -p "$POCL_CACHE_DIR"
fi
commit=$(git rev-parse --short HEAD)
git diff --quiet HEAD || echo "bench/test_suite.sh: uncommitted changes are not in the clone" >&2
git clone -q . "$tmp/clone"
comment="bench/test_suite.sh (rows suite_* and run_after_*) and the commands given (the other rows):
wall time (s) and peak RSS (MB) from GNU time; each row with its commit, machine, date and CPU
target (bench/results.sh)"
row() {  # name seconds kb note command
  python3 bench/results_row.py "$out" "$comment" name="$1" wall_s="$2" peak_rss_mb="$(($3 / 1024))" \
    note="$4" commit="$commit" date="$(date -u +%F)" machine="$(result_machine)" \
    cpu_target="$(result_target)" command="$5"
}
env_note=$([ "$mode" = cold ] && echo "POCL_CACHE_DIR=\$(mktemp -d) " || true)
(cd "$tmp/clone" && /usr/bin/time -f '%e %M' -o "$tmp/time" scripts/test.sh > "$tmp/test.log" 2>&1) ||
  { tail -30 "$tmp/test.log" >&2; echo "bench/test_suite.sh: the suite failed" >&2; exit 1; }
read -r secs kb < "$tmp/time"
summary=$(grep -E 'tests passed, [0-9]+ tests failed out of' "$tmp/test.log" | tail -1)
ctest_s=$(sed -n 's/^Total Test time (real) = *\([0-9.]*\) sec/\1/p' "$tmp/test.log" | tail -1)
row "suite_$mode" "$secs" "$kb" "$summary; ctest ${ctest_s:-?} s" \
  "git clone . CLONE && cd CLONE && ${env_note}scripts/test.sh"
(cd "$tmp/clone" && /usr/bin/time -f '%e %M' -o "$tmp/time" scripts/run.sh -q -o "$tmp/table.txt" \
  > /dev/null 2>&1)
read -r secs kb < "$tmp/time"
row "run_after_suite_$mode" "$secs" "$kb" \
  "scripts/run.sh in the clone after scripts/test.sh, with the suite's PoCL cache" \
  "cd CLONE && scripts/run.sh -q -o TMP/table.txt"
cat "$out"
