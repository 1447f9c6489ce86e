#!/usr/bin/env python3
"""Each API envelope's guaranteed MTS against every emulated implementation's worst case, from
`depthprec table --profile P --format-out json` for the ideal, llvmpipe and softpipe profiles and
the envelopes' adversaries (their rows bounded under the envelope's own model). Per envelope: the
rows where its bound lies below a profile's MTS (there should be none but where a driver leaves
the envelope), and per technique the median of its bound over the default table's bound (the
ideal profile's rows, under the default model) and over its own adversary's MTS.
Usage: envelope_bounds.py IDEAL.json LLVMPIPE.json SOFTPIPE.json ENVELOPE.json..."""
import json
import math
import statistics
import sys


def rows(path):
    with open(path) as f:
        doc = json.load(f)
    out = {}
    for r in doc["rows"]:
        key = (r["technique"], r["format"], r["depth_range"], r["z"])
        out[key] = r
    return doc["rows"][0].get("profile", path), out


def value(r, field):
    v = r.get(field) if r else None
    return v if isinstance(v, (int, float)) and math.isfinite(v) and v > 0 else math.nan


def resolved(r):
    return r is not None and r.get("verdict") == "resolved"


def main():
    tables = [rows(p) for p in sys.argv[1:]]
    ideal = tables[0][1]
    profiles = tables[:3]
    for name, env in tables[3:]:
        model = next(iter(env.values())).get("bound_model")
        print(f"## {name} (bound model {model})")
        below, checked, unbounded = [], 0, 0
        for key, r in env.items():
            bound = value(r, "mts_bound")
            if not resolved(r):
                continue
            if math.isnan(bound):
                unbounded += 1
                continue
            for pname, t in profiles + [(name, env)]:
                other = t.get(key)
                if not resolved(other):
                    continue
                checked += 1
                if bound < value(other, "mts"):
                    below.append((pname, key, bound, value(other, "mts")))
        print(f"resolved rows with a bound, checked against {len(profiles) + 1} worst cases: "
              f"{checked} comparisons, {len(below)} below; {unbounded} resolved rows unbounded")
        for pname, key, bound, mts in below:
            print(f"  below {pname}: {'/'.join(map(str, key[:3]))} z = {key[3]:g}: "
                  f"bound {bound:.4g} < mts {mts:.4g} ({mts / bound:.3f}x)")
        print("| technique | rows | bound / default bound | bound / own adversary's mts |")
        print("|---|---|---|---|")
        by_technique = {}
        for key, r in env.items():
            bound = value(r, "mts_bound")
            base = value(ideal.get(key), "mts_bound")
            own = value(r, "mts")
            if resolved(r) and not math.isnan(bound) and not math.isnan(base):
                by_technique.setdefault(key[0], []).append((bound / base, bound / own))
        for t, v in by_technique.items():
            print(f"| {t} | {len(v)} | {statistics.median(a for a, _ in v):.3g} | "
                  f"{statistics.median(b for _, b in v):.3g} |")
        print()


if __name__ == "__main__":
    main()
