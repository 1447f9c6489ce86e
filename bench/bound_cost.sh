#!/usr/bin/env bash
# What the guaranteed MTS costs the default table: the table with mts_bound (this build) against a
# build from before it (BASE_BIN, e.g. a worktree of 9318347), run alternately (rounds times each,
# so the VM's drift falls on both alike): wall medians, peak RSS, their ratio; and whether the
# table without its mts_bound columns is byte-identical to the base's. Prints and writes
# bench/results/bound_cost.txt (bench/results.sh), headed by commit, machine, date and CPU target.
# Usage: BASE_BIN=/path/to/old/depthprec bench/bound_cost.sh [rounds]
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/results.sh
rounds=${1:-3}
base=${BASE_BIN:?name the build from before the bound: BASE_BIN=.../depthprec}
bin=${DEPTHPREC:-build/depthprec}
out=$(mktemp -d)
result=$(result_path bound_cost txt)
trap 'rm -rf "$out" "$result.tmp"' EXIT

run() {  # name, binary: appends "name seconds MB" (bench/results.sh table_run)
  table_run "$out" "$1" "$2"
}

measure() {
  result_header "bench/bound_cost.sh $rounds: depthprec table (worst case, the default) with" \
    "mts_bound ($bin) and without (BASE_BIN $base), alternately"
  for _ in $(seq "$rounds"); do
    run base "$base"
    run bound "$bin"
  done
  python3 - "$out" <<'PY'
import csv, io, statistics, sys
out = sys.argv[1]
runs = [l.split() for l in open(f"{out}/runs")]
med = {n: statistics.median(float(s) for m, s, _ in runs if m == n) for n in ("base", "bound")}
rss = {n: max(int(k) for m, _, k in runs if m == n) for n in ("base", "bound")}
for n in ("base", "bound"):
    print(f"{n:6s} wall median {med[n]:.2f} s over {sum(1 for r in runs if r[0] == n)} runs, "
          f"peak RSS {rss[n]} MB")
print(f"bound / base: {med['bound'] / med['base']:.3f}")
rows = list(csv.reader(open(f"{out}/bound.csv")))
keep = [i for i, c in enumerate(rows[0]) if not c.endswith(" mts_bound")]
stripped = io.StringIO()
w = csv.writer(stripped, lineterminator="\n")
for r in rows:
    w.writerow([r[i] for i in keep])
same = stripped.getvalue() == open(f"{out}/base.csv").read()
print("table without its mts_bound columns byte-identical to the base's:", "yes" if same else "NO")
PY
}

measure | tee "$result.tmp"
mv "$result.tmp" "$result"
