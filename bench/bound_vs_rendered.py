#!/usr/bin/env python3
"""Rendered MTS rows against their mts_bound: one table line per resolved row and a summary per
driver. Usage: bench/bound_vs_rendered.py [--bounds MTS.json] NAME=RENDERED [NAME=RENDERED ...]
RENDERED is the JSON of `depthprec render --format-out json`, or an unfinished run's journal
(OUTPUT.rows.jsonl); files given the same NAME are one driver's rows. --bounds takes each row's
mts_bound from the JSON of `depthprec mts SCENE --format-out json` (the row of the same pair and
z) instead of the rendering's own, for renderings made by an older build
(bench/bound_vs_rendered.sh runs it on fresh renderings)."""
import json
import statistics
import sys


def rows_of(path):
    if path.endswith(".jsonl"):
        rows = []
        for line in open(path):
            try:
                rows.append(json.loads(line))
            except json.JSONDecodeError:  # a live journal's last line, still being written
                continue
        return [r for r in rows if "journal_of" not in r]
    return json.load(open(path))["rows"]


def key(r):
    return (r["technique"], r["format"], r["depth_range"], r["z"])


args = sys.argv[1:]
bounds = None
if args[:1] == ["--bounds"]:
    bounds = {key(r): r.get("mts_bound") for r in rows_of(args[1])}
    args = args[2:]
runs = {}
for a in args:
    name, path = a.split("=", 1)
    runs.setdefault(name, []).extend(rows_of(path))
print("| driver | pair | z | rendered mts | mts_bound | bound / rendered |")
print("|---|---|---|---|---|---|")
summary = []
for name, rows_in in runs.items():
    below, rows, ratios, unbounded, unmatched = 0, 0, [], 0, 0
    for r in rows_in:
        if r["verdict"] != "resolved":
            continue
        rows += 1
        if bounds is not None and key(r) not in bounds:
            unmatched += 1
            continue
        b = bounds[key(r)] if bounds is not None else r.get("mts_bound")
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
        f"median {statistics.median(ratios):.3g}, max {max(ratios):.3g}"
        + (f"; {unmatched} with no row in --bounds" if unmatched else ""))
print()
print("\n".join(summary))
