#!/usr/bin/env python3
"""Puts one measured row into a result CSV of bench/results/ (docs/performance.md), replacing the
row of the same name and keeping every other row, each with its own provenance: a file of rows
measured on different days, commits or machines says so row by row. Comment lines (#) at the top
are kept; a new file starts with the COMMENT given.

Usage: results_row.py FILE COMMENT name=VALUE...   (the columns: COLUMNS below)"""
import csv
import io
import os
import sys

COLUMNS = ["name", "wall_s", "peak_rss_mb", "note", "commit", "date", "machine", "cpu_target",
           "command"]


def main():
    path, comment = sys.argv[1], sys.argv[2]
    row = dict(arg.split("=", 1) for arg in sys.argv[3:])
    unknown = set(row) - set(COLUMNS)
    if unknown or "name" not in row:
        sys.exit(f"results_row.py: columns are {', '.join(COLUMNS)} (name required); "
                 f"got {', '.join(sorted(row))}")
    head, rows = [f"# {line}\n" for line in comment.split("\n")], []
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            lines = f.readlines()
        head = [line for line in lines if line.startswith("#")]
        rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    new = {c: row.get(c, "") for c in COLUMNS}
    for i, r in enumerate(rows):
        if r["name"] == new["name"]:
            rows[i] = new
            break
    else:
        rows.append(new)
    out = io.StringIO()
    w = csv.DictWriter(out, COLUMNS, lineterminator="\n")
    w.writeheader()
    w.writerows({c: r.get(c, "") for c in COLUMNS} for r in rows)
    with open(path + ".tmp", "w", encoding="utf-8") as f:
        f.write("".join(head) + out.getvalue())
    os.replace(path + ".tmp", path)


main()
