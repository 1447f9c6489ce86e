#!/usr/bin/env python3
"""Rendered MTS rows against their mts_bound: one table line per resolved row and a summary per
driver. Usage: bench/bound_vs_rendered.py [--bounds MTS.json] NAME=RENDERED [NAME=RENDERED ...]
RENDERED is the JSON of `depthprec render --format-out json`, an unfinished run's journal
(OUTPUT.rows.jsonl), or a table this script printed (bench/results/bound_vs_rendered*.txt: its
rendered MTS at six significant digits, its z matched to the --bounds row within 10^-5); files
given the same NAME are one driver's rows. --bounds takes each row's
mts_bound from the JSON of `depthprec mts SCENE --format-out json` (the row of the same pair and
z) instead of the rendering's own, for renderings made by an older build
(bench/bound_vs_rendered.sh runs it on fresh renderings)."""
import json
import statistics
import sys


def rows_of(path):
    if path.endswith(".txt"):  # a printed table: | driver | pair | z | rendered mts | ... |
        rows = []
        for line in open(path):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if not line.startswith("| ") or len(cells) != 6 or cells[0] == "driver":
                continue
            try:
                z, mts = float(cells[2]), float(cells[3])
            except ValueError:  # the header's rule
                continue
            technique, fmt, depth_range = cells[1].split("/")
            rows.append({"technique": technique, "format": fmt, "depth_range": depth_range,
                         "z": z, "mts": mts, "verdict": "resolved"})
        return rows
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


def bound_of(r):
    """The --bounds row of r's pair and z; a printed z (six digits) matches within 10^-5."""
    if key(r) in bounds:
        return bounds[key(r)]
    near = [k for k in bounds if k[:3] == key(r)[:3] and abs(k[3] - r["z"]) <= 1e-5 * k[3]]
    return bounds[near[0]] if len(near) == 1 else KeyError
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
        b = bound_of(r) if bounds is not None else r.get("mts_bound")
        if b is KeyError:
            unmatched += 1
            continue
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
