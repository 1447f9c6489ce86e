#!/usr/bin/env python3
"""Rendered MTS rows against their mts_bound: one table line per resolved row and a summary per
driver. Usage: bench/bound_vs_rendered.py NAME=RENDERED.json [NAME=RENDERED.json ...]
(the JSON of `depthprec render --format-out json`; bench/bound_vs_rendered.sh runs it)."""
import json
import statistics
import sys

runs = [(a.split("=", 1)[0], json.load(open(a.split("=", 1)[1]))) for a in sys.argv[1:]]
print("| driver | pair | z | rendered mts | mts_bound | bound / rendered |")
print("|---|---|---|---|---|---|")
summary = []
for name, run in runs:
    below, rows, ratios, unbounded = 0, 0, [], 0
    for r in run["rows"]:
        if r["verdict"] != "resolved":
            continue
        rows += 1
        b = r.get("mts_bound")
        if not isinstance(b, (int, float)):
            unbounded += 1
            continue
        ratios.append(b / r["mts"])
        below += b < r["mts"]
        pair = f"{r['technique']}/{r['format']}/{r['depth_range']}"
        print(f"| {name} | {pair} | {r['z']:g} | {r['mts']:.6g} | {b:.6g} | {b / r['mts']:.3g} |")
    summary.append(
        f"{name}: {rows} resolved rows, {len(ratios)} with a finite bound, {unbounded} without; "
        f"bound below the rendered MTS on {below}; bound / rendered: min {min(ratios):.3g}, "
        f"median {statistics.median(ratios):.3g}, max {max(ratios):.3g}")
print()
print("\n".join(summary))
