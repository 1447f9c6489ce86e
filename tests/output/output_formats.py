#!/usr/bin/env python3
"""Every command's JSON and CSV read by real parsers (Python's json and csv modules).

JSON: a header with format_version (an integer) and kind; numbers are JSON numbers (a string
that reads as a number is an error; non-finite values are the strings "inf", "-inf", "nan");
the scene's name where a scene ran. CSV: one header line of unique, non-empty names, then rows
of the same length; the columns that hold numbers parse as numbers, and hold the JSON's values
exactly (binary64 round trip).

usage: output_formats.py DEPTHPREC
"""
import csv
import io
import json
import math
import os
import subprocess
import sys

EXE = sys.argv[1]
# The worst case (the default sampling) in rounds of 10 orientations: its rows and columns as the
# default's, in a tenth of the frames.
SCENE = ("-t standard,reversed -f unorm24 --kernel 24x24 --frames 4 --distances 2,1000 "
         "--set worst_case.round_size=10 --no-timing -q")
AUDIT_SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "audit",
                           "decal_wall.gltf")
NON_FINITE = {"inf", "-inf", "nan"}
failures = []


def run(args):
    p = subprocess.run([EXE] + args.split(), capture_output=True, text=True, timeout=300)
    if p.returncode != 0:
        raise SystemExit(f"depthprec {args}: exit {p.returncode}\n{p.stderr}")
    return p.stdout


def fail(what):
    failures.append(what)


def looks_numeric(s):
    try:
        float(s)
        return True
    except ValueError:
        return False


def walk(v, path, where):
    """No number hidden in a string anywhere in a JSON document."""
    if isinstance(v, dict):
        for k, x in v.items():
            walk(x, f"{path}.{k}", where)
    elif isinstance(v, list):
        for i, x in enumerate(v):
            walk(x, f"{path}[{i}]", where)
    elif isinstance(v, str) and looks_numeric(v) and v not in NON_FINITE:
        fail(f"{where}: {path} is the string {v!r}, not a JSON number")


def number(s):
    return float(s) if s not in NON_FINITE else {"inf": math.inf, "-inf": -math.inf}.get(s, math.nan)


# (command line, kind, runs a scene, numeric CSV columns, (JSON list, CSV column, JSON field)
#  whose values must agree exactly row by row, or None)
COMMANDS = [
    (f"mts {SCENE}", "mts", True, ["z", "lo", "hi", "mts_seen", "vertex_bound", "probes"],
     ("rows", "mts", "mts")),
    (f"table {SCENE}", "table", True, ["z", "vertex_bound"], None),
    (f"table --attribute {SCENE}", "table", True, ["z", "vertex_bound"], None),
    (f"cost {SCENE}", "cost", True, ["median mts/vb", "unresolvable"], None),
    (f"pipelines {SCENE}", "pipelines", True, ["double/separate verdicts"], None),
    (f"compare {SCENE}", "compare", True, ["z", "emulated", "rendered"],
     ("records", "rendered", "rendered_mts")),
    ("lj --samples 10000 --no-timing", "lj", False, ["ae"], None),
    ("select --samples 10000", "select", False, ["rank", "E", "M", "ae", "x best"],
     ("ranking", "ae", "ae")),
    ("lj-table --samples 1000 -q --no-timing", "lj-table", False, ["f/d", "bits", "ae"], None),
    ("resolve -t standard -f unorm24 --near 1 --far 1000 --curve", "resolve", False,
     ["distance", "depth", "code", "gap_below", "resolution"], ("rows", "depth", "depth")),
    # readback maps depths on the host: the scene's pairs and distances, not its kernel or frames
    ("readback -t standard,reversed -f unorm24 --distances 2,1000 --no-timing -q", "readback",
     True,
     ["z", "code", "read", "error", "rel_error", "storage_error", "arithmetic_error", "code_gap"],
     ("rows", "read", "read")),
    ("formats --value 0.5", "formats", False, ["value", "code", "stored", "rel. error"],
     ("round_trips", "stored", "stored")),
    ("formats", "formats", False, ["bits", "largest", "codes"], ("formats", "largest", "largest")),
    ("devices", "devices", False, ["CUs", "mem GiB"], None),
    ("advise --range 10,100 --separation 0.05 -t standard,linear -f unorm24 --kernel 24x24 "
     "--frames 4 --set worst_case.round_size=10 --no-timing -q", "advise", True,
     ["smallest near", "fails at z", "largest far", "steps"],
     None),
    ("world -t standard,reversed -f unorm24 --kernel 24x24 --frames 4 --separation 0.05 "
     "--set sampling=paper --no-timing -q", "world", True,
     ["absolute mts at 0", "absolute limit R", "absolute spacing", "absolute mts below",
      "camera_relative limit R", "camera_relative spacing"], None),
    (f"table --profiles ideal,llvmpipe {SCENE}", "profiles", True, ["z"], None),
    (f"mts --profiles ideal,llvmpipe {SCENE}", "profiles", True,
     ["z", "ideal", "llvmpipe", "spread"], None),
    (f"audit {AUDIT_SCENE} -t standard,reversed -f unorm24 --size 160x90 --set sampling=paper "
     "--no-timing -q", "audit", True,
     ["fighting_pixels", "coplanar_pixels", "covered_pixels", "pair_pixels", "eye_depth",
      "min_separation", "mts", "offset_needed", "near_that_resolves", "bias_units"], None),
    (f"bias {SCENE}", "bias", True,
     ["z", "units", "factor", "set factor", "set units", "offset", "eye separation", "MTS"], None),
]

for args, kind, scened, numeric, agree in COMMANDS:
    where = f"depthprec {args}"
    doc = json.loads(run(args + " --format-out json"))
    if not isinstance(doc.get("format_version"), int):
        fail(f"{where} --format-out json: format_version is not an integer")
    if doc.get("kind") != kind:
        fail(f"{where} --format-out json: kind is {doc.get('kind')!r}, not {kind!r}")
    if scened and not doc.get("scene_name"):
        fail(f"{where} --format-out json: no scene_name")
    walk(doc, "$", where + " --format-out json")

    text = run(args + " --format-out csv")
    rows = list(csv.reader(io.StringIO(text, newline="")))
    if not rows:
        fail(f"{where} --format-out csv: empty")
        continue
    header, body = rows[0], rows[1:]
    if any(not h for h in header) or len(set(header)) != len(header):
        fail(f"{where} --format-out csv: header {header} has empty or repeated names")
    if not body:
        fail(f"{where} --format-out csv: no rows")
    for i, r in enumerate(body):
        if len(r) != len(header):
            fail(f"{where} --format-out csv: row {i + 1} has {len(r)} fields, header {len(header)}")
    for col in numeric:
        if col not in header:
            fail(f"{where} --format-out csv: no column {col!r} in {header}")
            continue
        k = header.index(col)
        for r in body:
            if r[k] and not looks_numeric(r[k]):
                fail(f"{where} --format-out csv: {col} = {r[k]!r} is not a number")
    if agree:
        key, col, field = agree
        k = header.index(col)
        csv_values = [number(r[k]) for r in body if r[k]]
        json_values = [number(x[field]) if isinstance(x[field], str) else float(x[field])
                       for x in doc[key] if x.get(field) is not None]
        same = len(csv_values) == len(json_values) and all(
            a == b or (math.isnan(a) and math.isnan(b)) for a, b in zip(csv_values, json_values))
        if not same:
            fail(f"{where}: CSV {col} {csv_values} differs from JSON {field} {json_values}")

# audit's CSV holds the fighting and the coplanar pairs, told apart by `kind`; the coplanar rows'
# pair_pixels are the JSON's coplanar_pixels_lost, in order.
COPLANAR = AUDIT_SCENE.replace("decal_wall.gltf", "slab_railing.gltf")
audit_args = f"audit {COPLANAR} -t standard -f unorm24 --size 160x90 --no-fixes --no-timing -q"
audit_doc = json.loads(run(audit_args + " --format-out json"))
audit_csv = list(csv.DictReader(io.StringIO(run(audit_args + " --format-out csv"), newline="")))
kinds = {r.get("kind") for r in audit_csv}
if not kinds <= {"fight", "coplanar", "none"}:
    fail(f"audit --format-out csv: kind holds {kinds}, not fight, coplanar or none")
lost = [p["coplanar_pixels_lost"] for s in audit_doc["setups"] for p in s["coplanar_pairs"]]
rows = [int(r["pair_pixels"]) for r in audit_csv if r.get("kind") == "coplanar"]
if not lost or rows != lost:
    fail(f"audit CSV coplanar rows' pair_pixels {rows} differ from JSON coplanar_pixels_lost {lost}")

# What text shows with marks is in CSV as columns: the flags and, with --attribute, the factor.
table = list(csv.reader(io.StringIO(run(f"table --attribute {SCENE} --format-out csv"))))
for col in ("standard/unorm24/gl flags", "standard/unorm24/gl dominant"):
    if col not in table[0]:
        fail(f"table --attribute --format-out csv: no column {col!r}")
dominant = table[0].index("standard/unorm24/gl dominant")
if any(r[dominant] not in ("storage", "arithmetic", "vertex") for r in table[1:]):
    fail(f"table --attribute CSV: dominant column holds {[r[dominant] for r in table[1:]]}")

for f in failures:
    print("FAIL:", f)
print(f"{len(COMMANDS)} commands, {len(failures)} failures")
sys.exit(1 if failures else 0)
