#!/usr/bin/env python3
"""The layer order of host/ (docs/architecture.md, "Layers"), enforced: a file may include its own
folder, the folders of lower layers, and the headers host and kernels both compile (interface/,
formats/), never a folder of its own rank or above, and never a kernel source (kernels/: the
kernels reach the host embedded, as text). Prints each include against the order as FILE:LINE and
exits 1; exits 0 when there is none.

Usage: check_layers.py [SOURCE_DIR]        checks SOURCE_DIR/host (default: this repository)
       check_layers.py --self-test         checks that an include against the order is found
"""
import os
import re
import sys
import tempfile

# Lowest first; folders on one line are side by side (neither includes the other).
LAYERS = [
    ["base"],
    ["model"],
    ["runtime"],
    ["mts", "lj"],
    ["bias", "analysis"],
    ["audit"],
    ["output"],
    ["batch", "render"],
    ["cli"],
]
RANK = {folder: rank for rank, folders in enumerate(LAYERS) for folder in folders}
INCLUDE = re.compile(r'^\s*#\s*include\s+"host/([^/"]+)/')
KERNEL_INCLUDE = re.compile(r'^\s*#\s*include\s+"kernels/')


def violations(root):
    found = []
    host = os.path.join(root, "host")
    for folder in sorted(os.listdir(host)):
        path = os.path.join(host, folder)
        if not os.path.isdir(path):
            continue
        if folder not in RANK:
            found.append(f"host/{folder}: a folder the layer order does not name")
            continue
        for dirpath, _, files in os.walk(path):
            for name in sorted(files):
                if not name.endswith((".h", ".cpp")):
                    continue
                rel = os.path.relpath(os.path.join(dirpath, name), root)
                with open(os.path.join(dirpath, name), encoding="utf-8") as f:
                    for number, line in enumerate(f, 1):
                        if KERNEL_INCLUDE.match(line):
                            found.append(f"{rel}:{number}: includes a kernel source "
                                         f"({line.strip()}): shared headers are in interface/")
                            continue
                        m = INCLUDE.match(line)
                        if not m or m.group(1) == folder:
                            continue
                        target = m.group(1)
                        if target not in RANK:
                            found.append(f"{rel}:{number}: includes host/{target}/, a folder "
                                         "the layer order does not name")
                        elif RANK[target] >= RANK[folder]:
                            found.append(f"{rel}:{number}: {folder} includes {target} "
                                         f"({line.strip()}): against the layer order")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as root:
        for folder, text in [("base", ""), ("model", '#include "host/base/x.h"\n'),
                             ("mts", '#include "host/model/x.h"\n#include "host/output/y.h"\n'),
                             ("lj", '#include "host/mts/z.h"\n'),
                             ("output", '#include "interface/x.h"\n#include "kernels/y.cl"\n')]:
            os.makedirs(os.path.join(root, "host", folder))
            with open(os.path.join(root, "host", folder, "a.cpp"), "w") as f:
                f.write(text)
        got = violations(root)
        want = ["host/mts/a.cpp:2:", "host/lj/a.cpp:1:", "host/output/a.cpp:2:"]
        ok = len(got) == 3 and all(any(g.startswith(w) for g in got) for w in want)
        print("\n".join(got))
        print("self-test " + ("passed" if ok else "FAILED: expected " + ", ".join(want)))
        return 0 if ok else 1


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    found = violations(root)
    for v in found:
        print(v)
    print(f"{len(found)} include(s) against the layer order")
    return 1 if found else 0


sys.exit(main())
