#!/usr/bin/env python3
"""Row-by-row ratios of two MTS tables (`depthprec table --format-out csv`): how many resolved
rows of B lie above / below A by more than 5 % and 20 %, the median and largest ratio, and, for a
worst-case table, its convergence column. Usage: table_ratios.py A.csv B.csv [label]"""
import csv
import math
import statistics
import sys


def cells(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    pairs = [c for c in rows[0] if "/" in c and " " not in c]
    out = {}
    for r in rows:
        for p in pairs:
            try:
                v = float(r[p])
            except ValueError:  # a verdict where there is no MTS
                continue
            if math.isfinite(v):
                out[(p, r["z"])] = (v, r.get(p + " convergence", ""))
    return out


def main():
    a, b = cells(sys.argv[1]), cells(sys.argv[2])
    label = sys.argv[3] if len(sys.argv) > 3 else "B/A"
    keys = sorted(set(a) & set(b))
    ratios = [b[k][0] / a[k][0] for k in keys if a[k][0] > 0]
    up5 = sum(r > 1.05 for r in ratios)
    up20 = sum(r > 1.20 for r in ratios)
    down5 = sum(r < 1 / 1.05 for r in ratios)
    below = sum(r < 1 for r in ratios)
    print(f"{label}: {len(ratios)} rows resolved in both; above by >5 %: {up5}, >20 %: {up20}; "
          f"below at all: {below}, by >5 %: {down5}; median ratio {statistics.median(ratios):.4f}, "
          f"largest {max(ratios):.3f}, smallest {min(ratios):.3f}")
    conv = [float(b[k][1]) for k in keys if b[k][1] != ""]
    if conv:
        print(f"  convergence of B: 0 in {sum(c == 0 for c in conv)} of {len(conv)} rows, "
              f"<= 0.01 in {sum(c <= 0.01 for c in conv)}, median of the rest "
              f"{statistics.median([c for c in conv if c > 0.01] or [0]):.4f}, largest {max(conv):.4f}")
    by_pair = {}
    for k in keys:
        by_pair.setdefault(k[0], []).append(b[k][0] / a[k][0])
    for p, rs in by_pair.items():
        print(f"  {p:34s} median {statistics.median(rs):.3f}  max {max(rs):.3f}  "
              f">5 %: {sum(r > 1.05 for r in rs)} of {len(rs)}")


main()
