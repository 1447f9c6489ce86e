#!/usr/bin/env python3
"""How tight the guaranteed MTS is against what the emulated implementations witness: the default
table (the ideal pipeline's worst case, with mts_bound under the default model) beside the same
table under the llvmpipe and softpipe profiles (`depthprec table --format-out csv`). Per pair and
over every row resolved in all three with a finite bound: the median of llvmpipe's and softpipe's
MTS over the ideal one, of mts_bound over the ideal MTS, and of mts_bound over the largest of the
three. Usage: bound_tightness.py IDEAL.csv LLVMPIPE.csv SOFTPIPE.csv"""
import csv
import math
import statistics
import sys


def table(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def number(text):
    try:
        v = float(text)
    except ValueError:
        return math.nan
    return v if math.isfinite(v) and v > 0 else math.nan


def main():
    ideal, llvm, soft = (table(p) for p in sys.argv[1:4])
    pairs = [c for c in ideal[0] if "/" in c and " " not in c]
    print("| pair | rows | llvmpipe / ideal | softpipe / ideal | bound / ideal | bound / largest |")
    print("|---|---|---|---|---|---|")
    every = {k: [] for k in ("l", "s", "b", "m")}
    for p in pairs:
        got = {k: [] for k in every}
        for a, b, c in zip(ideal, llvm, soft):
            i, l, s = number(a[p]), number(b[p]), number(c[p])
            bound = number(a[p + " mts_bound"])
            if any(math.isnan(v) for v in (i, l, s, bound)):
                continue
            got["l"].append(l / i)
            got["s"].append(s / i)
            got["b"].append(bound / i)
            got["m"].append(bound / max(i, l, s))
        if not got["b"]:
            continue
        med = {k: statistics.median(v) for k, v in got.items()}
        print(f"| {p} | {len(got['b'])} | {med['l']:.2f} | {med['s']:.2f} | {med['b']:.2f} | "
              f"{med['m']:.2f} (least {min(got['m']):.2f}) |")
        for k in every:
            every[k] += got[k]
    med = {k: statistics.median(v) for k, v in every.items()}
    print(f"| every pair | {len(every['b'])} | {med['l']:.2f} | {med['s']:.2f} | {med['b']:.2f} | "
          f"{med['m']:.2f} (least {min(every['m']):.2f}) |")


main()
