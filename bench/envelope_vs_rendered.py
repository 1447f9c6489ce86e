#!/usr/bin/env python3
"""The API envelopes' guaranteed MTS against real rasterizers: the rendered MTS of each row of
data/validation.json on llvmpipe and softpipe (the tables bench/bound_vs_rendered.sh wrote) held
against each envelope's mts_bound for the same row (`depthprec mts data/validation.json
--set bound_model=E --format-out json`). A rendered MTS above an envelope's bound is a driver
outside the envelope, or an envelope read wrongly: listed with the row's dominant term.
Usage: envelope_vs_rendered.py RENDERED.txt... -- NAME=BOUNDS.json..."""
import json
import math
import statistics
import sys


def rendered_rows(path):
    """(driver, pair, z) -> rendered mts from a bound_vs_rendered table."""
    out = {}
    with open(path) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) != 6 or cells[0] in ("driver", "---"):
                continue
            try:
                out[(cells[0], cells[1], float(cells[2]))] = float(cells[3])
            except ValueError:
                continue
    return out


def bound_rows(path):
    with open(path) as f:
        doc = json.load(f)
    out = {}
    for r in doc["rows"]:
        label = f'{r["technique"]}/{r["format"]}/{r["depth_range"]}'
        out[(label, float(r["z"]))] = r
    return out


def main():
    split = sys.argv.index("--")
    rendered = {}
    for path in sys.argv[1:split]:
        rendered.update(rendered_rows(path))
    for arg in sys.argv[split + 1:]:
        name, path = arg.split("=", 1)
        bounds = bound_rows(path)
        print(f"## {name}")
        for driver in sorted({k[0] for k in rendered}):
            ratios, above, unbounded = [], [], 0
            for (d, pair, z), mts in sorted(rendered.items()):
                if d != driver or not math.isfinite(mts):
                    continue
                r = bounds.get((pair, z))
                b = r.get("mts_bound") if r else None
                if not isinstance(b, (int, float)) or not math.isfinite(b):
                    unbounded += 1
                    continue
                ratios.append(b / mts)
                if b < mts:
                    above.append((pair, z, mts, b, r.get("bound_by", "")))
            if not ratios:
                continue
            print(f"{driver}: {len(ratios)} rendered rows with a bound ({unbounded} without), "
                  f"{len(above)} above it; bound / rendered min {min(ratios):.3g}, median "
                  f"{statistics.median(ratios):.3g}, max {max(ratios):.3g}")
            for pair, z, mts, b, by in above:
                print(f"  {driver} {pair} z = {z:g}: rendered {mts:.4g} > bound {b:.4g} "
                      f"({mts / b:.3f}x; bound_by {by})")
        print()


if __name__ == "__main__":
    main()
