#!/usr/bin/env bash
# Wall time and peak RSS (GNU time) of the depthprec commands docs/performance.md names, one run
# each, PoCL's kernel cache warm unless the row says otherwise (NEWDIR: an empty directory made
# for the run). Each row goes into bench/results/commands.csv (bench/results.sh: OUT=FILE
# elsewhere; commands-haswell.csv under POCL_LLVM_CPU_NAME=haswell) with its own commit, machine,
# date and CPU target, replacing the row of that name: run the rows a change affects, and the
# file says which rows are of which commit. The rows' outputs go to a temporary directory.
# Usage: bench/command_figures.sh [NAME...]      (no NAME: every row, about half an hour;
#        bench/command_figures.sh --list           the names and commands)
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
bin=build/depthprec
d10=1.005,4,16,64,256,1024,4096,16384,65536,262144
# name | environment (NEWDIR: a fresh empty directory) | depthprec arguments (TMP: the run's
# temporary directory)
rows=$(cat <<ROWS
table_jobs1||table --format-out csv --no-timing -q -o TMP/t.csv --jobs 1
table_jobs2||table --format-out csv --no-timing -q -o TMP/t.csv --jobs 2
table_llvmpipe||table --profile llvmpipe -q --no-timing -o TMP/t.txt
table_softpipe||table --profile softpipe -q --no-timing -o TMP/t.txt
mts_standard_unorm24||mts -t standard -f unorm24 -q -o TMP/x.txt
mts_standard_unorm24_softpipe||mts -t standard -f unorm24 --profile softpipe -q -o TMP/x.txt
table_profiles||table --profiles ideal,llvmpipe -q --no-timing -o TMP/p.txt
one_pair_warm||mts -t standard -f unorm24 --distances 2 -q -o TMP/x.txt
one_pair_first_run|POCL_CACHE_DIR=NEWDIR|mts -t standard -f unorm24 --distances 2 -q -o TMP/x.txt
one_pair_nothing_kept|POCL_CACHE_DIR=NEWDIR DEPTHPREC_KERNEL_CACHE=off|mts -t standard -f unorm24 --distances 2 -q -o TMP/x.txt
lj||lj --buffer z --format unorm16 --near 1 --far 100 -o TMP/lj.txt
lj_table||lj-table --format-out markdown -q -o TMP/lj.md
table_attribute||table --attribute --format-out json -q -o TMP/attr.json
report||report -q -o TMP/r.html
advise_separation||advise --range 10,1000 --separation 0.05 -q -o TMP/a.txt
advise_relative||advise --range 100,1000 --relative 1e-4 -q -o TMP/a.txt
world||world --distance 100 --separation 0.01 --transforms absolute,camera_relative,relative_to_eye --no-timing -q -o TMP/w.txt
bias_standard_unorm24||bias -t standard -f unorm24 --distances $d10 -q -o TMP/b.txt
bias_reversed_float32||bias -t reversed -f float32 --distances $d10 -q -o TMP/b.txt
bias_log_vertex_unorm24||bias -t log_vertex -f unorm24 --distances $d10 -q -o TMP/b.txt
bias_default||bias -q --no-timing -o TMP/bias.txt
compare_validation||compare data/validation.json --format-out json -q -o TMP/v.json
memory_default||table --no-timing -q -o TMP/m.txt
memory_frames100||table -t standard,reversed -f unorm24 --frames 100 --no-timing -q -o TMP/m.txt
memory_frames400||table -t standard,reversed -f unorm24 --frames 400 --no-timing -q -o TMP/m.txt
memory_frames1000||table -t standard,reversed -f unorm24 --frames 1000 --no-timing -q -o TMP/m.txt
memory_kernel100||table -t standard,reversed -f unorm24 --kernel 100x100 --no-timing -q -o TMP/m.txt
memory_kernel200||table -t standard,reversed -f unorm24 --kernel 200x200 --no-timing -q -o TMP/m.txt
memory_kernel400||table -t standard,reversed -f unorm24 --kernel 400x400 --no-timing -q -o TMP/m.txt
ROWS
)
if [ "${1:-}" = --list ]; then
  echo "$rows" | awk -F'|' '{ printf "%-30s %s%sdepthprec %s\n", $1, $2, ($2 == "" ? "" : " "), $3 }'
  exit 0
fi
for name in "$@"; do
  echo "$rows" | cut -d'|' -f1 | grep -qx -- "$name" ||
    { echo "bench/command_figures.sh: no row '$name' (--list names them)" >&2; exit 2; }
done
out=$(result_path commands csv)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$(dirname "$out")"
comment="bench/command_figures.sh: wall time (s) and peak RSS (MB) of one run of each command, GNU time;
each row with its commit (+changes: host/, kernels/, interface/ or formats/ differed from it),
machine, date and CPU target (bench/results.sh); in a command NEWDIR is an empty directory made
for the run, TMP a temporary one"
while IFS='|' read -r name env args; do
  if [ $# -gt 0 ] && ! printf '%s\n' "$@" | grep -qx -- "$name"; then continue; fi
  env_words=()
  for e in $env; do
    [[ $e == *NEWDIR* ]] && e=${e//NEWDIR/$(mktemp -d -p "$tmp")}
    env_words+=("$e")
  done
  read -r -a argv <<<"${args//TMP/$tmp}"
  echo "$name: ${env:+$env }depthprec $args" >&2
  env "${env_words[@]}" /usr/bin/time -f '%e %M' -o "$tmp/time" "$bin" "${argv[@]}" > /dev/null
  read -r secs kb < "$tmp/time"
  python3 bench/results_row.py "$out" "$comment" name="$name" wall_s="$secs" \
    peak_rss_mb="$((kb / 1024))" commit="$(result_commit)" date="$(date -u +%F)" \
    machine="$(result_machine)" cpu_target="$(result_target)" \
    command="${env:+$env }depthprec $args"
  echo "  $secs s, $((kb / 1024)) MB" >&2
done <<<"$rows"
echo "wrote $out"
