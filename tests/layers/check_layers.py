#!/usr/bin/env python3
"""The layer order of host/ (docs/architecture.md, "Layers"), enforced. Three rules:

1. The order: a file may include its own folder, the folders of lower layers, and the headers host
   and kernels both compile (interface/, formats/), never a folder of its own rank or above, and
   never a kernel source (kernels/: the kernels reach the host embedded, as text).
2. No OpenCL where nothing launches a kernel: no file of host/render, host/analysis or host/audit
   includes the OpenCL runtime (host/runtime/opencl_runtime.h, cl.h, kernel_args.h, or <CL/...>),
   directly or through any header of the repository that does, except the audit's device pass
   (host/audit/audit_device.cpp). Passing an OpenClRuntime on takes a declaration
   (`class OpenClRuntime;`), not an include.
3. No include cycle within a folder: taking a header and its .cpp as one unit (x.h, x.cpp), no unit
   includes, directly or through others of its folder, a unit that includes it.

Prints each breach as FILE:LINE (a cycle: the folder and the includes that close it) and exits 1;
exits 0 when there is none.

Usage: check_layers.py [SOURCE_DIR]        checks SOURCE_DIR/host (default: this repository)
       check_layers.py --self-test         checks that a breach of each rule is found
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
    ["audit", "shadow"],
    ["output"],
    ["batch", "render"],
    ["cli"],
]
RANK = {folder: rank for rank, folders in enumerate(LAYERS) for folder in folders}
INCLUDE = re.compile(r'^\s*#\s*include\s+"host/([^/"]+)/')
KERNEL_INCLUDE = re.compile(r'^\s*#\s*include\s+"kernels/')
QUOTED_INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
CL_INCLUDE = re.compile(r'^\s*#\s*include\s+<CL/')

# Rule 2: the folders that launch no kernel, the OpenCL runtime's headers, the one file allowed.
NO_OPENCL = ["render", "analysis", "audit"]
OPENCL_HEADERS = {"host/runtime/opencl_runtime.h", "host/runtime/cl.h",
                  "host/runtime/kernel_args.h"}
OPENCL_ALLOWED = {"host/audit/audit_device.cpp"}


def host_files(root):
    """(folder, path relative to root) of every .h and .cpp under root/host, sorted."""
    host = os.path.join(root, "host")
    out = []
    for folder in sorted(os.listdir(host)):
        if not os.path.isdir(os.path.join(host, folder)):
            continue
        for dirpath, _, files in sorted(os.walk(os.path.join(host, folder))):
            for name in sorted(files):
                if name.endswith((".h", ".cpp")):
                    out.append((folder, os.path.relpath(os.path.join(dirpath, name), root)))
    return out


def read_lines(root, rel):
    with open(os.path.join(root, rel), encoding="utf-8") as f:
        return f.readlines()


class Includes:
    """The quoted includes of the repository's files, resolved to paths relative to root (from
    the root, as the build's include path has it, else beside the including file)."""

    def __init__(self, root):
        self.root = root
        self.cache = {}

    def of(self, rel):
        if rel not in self.cache:
            found = []
            for number, line in enumerate(read_lines(self.root, rel), 1):
                m = QUOTED_INCLUDE.match(line)
                if CL_INCLUDE.match(line):
                    found.append((number, "<CL/...>"))
                elif m:
                    for base in ("", os.path.dirname(rel)):
                        target = os.path.normpath(os.path.join(base, m.group(1)))
                        if os.path.isfile(os.path.join(self.root, target)):
                            found.append((number, target))
                            break
            self.cache[rel] = found
        return self.cache[rel]


def layer_violations(root):
    found = []
    host = os.path.join(root, "host")
    for folder in sorted(os.listdir(host)):
        if os.path.isdir(os.path.join(host, folder)) and folder not in RANK:
            found.append(f"host/{folder}: a folder the layer order does not name")
    for folder, rel in host_files(root):
        if folder not in RANK:
            continue
        for number, line in enumerate(read_lines(root, rel), 1):
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


def toward_opencl(includes, starts):
    """For every file the starts reach that reaches an OpenCL header: the file it includes one step
    nearer to one (a breadth-first search back from the headers, so chains are shortest)."""
    graph, todo = {}, list(starts)
    while todo:
        rel = todo.pop()
        if rel in graph or rel == "<CL/...>":
            continue
        graph[rel] = [target for _, target in includes.of(rel)]
        todo.extend(graph[rel])
    included_by = {}
    for rel, targets in graph.items():
        for target in targets:
            included_by.setdefault(target, []).append(rel)
    toward = {h: None for h in ["<CL/...>"] + sorted(OPENCL_HEADERS)}
    frontier = list(toward)
    while frontier:
        nearer = []
        for target in frontier:
            for rel in sorted(included_by.get(target, [])):
                if rel not in toward:
                    toward[rel] = target
                    nearer.append(rel)
        frontier = nearer
    return toward


def opencl_violations(root):
    includes, found = Includes(root), []

    def checked(rel):
        parts = rel.split(os.sep)
        return (len(parts) > 2 and parts[0] == "host" and parts[1] in NO_OPENCL
                and rel not in OPENCL_ALLOWED)

    files = [(folder, rel) for folder, rel in host_files(root) if checked(rel)]
    toward = toward_opencl(includes, [rel for _, rel in files])
    for folder, rel in files:
        for number, target in includes.of(rel):
            # An include of another checked file is reported there, once.
            if checked(target) or target not in toward:
                continue
            chain = [target]
            while toward[chain[-1]] is not None:
                chain.append(toward[chain[-1]])
            found.append(f"{rel}:{number}: {folder} includes OpenCL ({' -> '.join(chain)}): "
                         "pass an OpenClRuntime on as `class OpenClRuntime;`, or include the "
                         "OpenCL-free interface")
    return found


def cycle_violations(root):
    """Strongly connected units (x.h + x.cpp) of each folder, with the includes that join them."""
    includes = Includes(root)
    edges = {}  # unit -> {unit: "file:line"}
    for _, rel in host_files(root):
        unit = os.path.splitext(rel)[0]
        edges.setdefault(unit, {})
        for number, target in includes.of(rel):
            other = os.path.splitext(target)[0]
            if other != unit and os.path.dirname(other) == os.path.dirname(unit) \
                    and target.startswith("host/"):
                edges[unit].setdefault(other, f"{rel}:{number}")
    # Tarjan's strongly connected components, iteratively.
    index, low, stack, on_stack, components = {}, {}, [], set(), []
    for start in sorted(edges):
        if start in index:
            continue
        work = [(start, iter(sorted(edges[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            unit, children = work[-1]
            child = next(children, None)
            if child is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[unit])
                if low[unit] == index[unit]:
                    component = []
                    while True:
                        top = stack.pop()
                        on_stack.discard(top)
                        component.append(top)
                        if top == unit:
                            break
                    if len(component) > 1:
                        components.append(sorted(component))
            elif child not in index:
                index[child] = low[child] = len(index)
                stack.append(child)
                on_stack.add(child)
                work.append((child, iter(sorted(edges.get(child, {})))))
            elif child in on_stack:
                low[unit] = min(low[unit], index[child])
    found = []
    for component in sorted(components):
        members = set(component)
        joins = [f"{edges[u][v]} includes {os.path.basename(v)}"
                 for u in component for v in sorted(edges[u]) if v in members]
        names = ", ".join(os.path.basename(u) for u in component)
        found.append(f"{os.path.dirname(component[0])}: include cycle between {names} "
                     f"({'; '.join(joins)}): move what both need into a lower file")
    return found


def violations(root):
    return layer_violations(root) + opencl_violations(root) + cycle_violations(root)


def self_test():
    tree = {
        # rule 1: one upward, one on its own rank, one kernel source
        "host/base/a.cpp": "",
        "host/model/a.cpp": '#include "host/base/x.h"\n',
        "host/mts/a.cpp": '#include "host/model/x.h"\n#include "host/output/y.h"\n',
        "host/lj/a.cpp": '#include "host/mts/z.h"\n',
        "host/output/a.cpp": '#include "interface/x.h"\n#include "kernels/y.cl"\n',
        # rule 2: the runtime's headers; an evaluator that includes one; a header that declares
        # the runtime instead; a check of the allowed file
        "host/runtime/opencl_runtime.h": '#include "host/runtime/cl.h"\n',
        "host/runtime/cl.h": "#include <CL/opencl.hpp>\n",
        "host/runtime/kernel_args.h": '#include "host/runtime/cl.h"\n',
        "host/mts/evaluator.h": '#include "host/runtime/opencl_runtime.h"\n',
        "host/mts/clean.h": "class OpenClRuntime;\n",
        "host/render/direct.cpp": '#include "host/runtime/kernel_args.h"\n',
        "host/render/through.h": '#include "host/mts/clean.h"\n#include "host/mts/evaluator.h"\n',
        "host/render/through.cpp": '#include "host/render/through.h"\n',
        "host/analysis/raw.cpp": "#include <CL/cl.h>\n",
        "host/audit/audit_device.cpp": '#include "host/runtime/kernel_args.h"\n',
        "host/audit/clean.cpp": '#include "host/mts/clean.h"\n',
        # rule 3: a cycle through a header and the other unit's .cpp; a one-way pair
        "host/batch/p.h": "",
        "host/batch/p.cpp": '#include "host/batch/p.h"\n#include "host/batch/q.h"\n',
        "host/batch/q.h": '#include "host/batch/p.h"\n',
        "host/batch/r.h": '#include "host/batch/p.h"\n',
    }
    want = ["host/mts/a.cpp:2:", "host/lj/a.cpp:1:", "host/output/a.cpp:2:",
            "host/render/direct.cpp:1:", "host/render/through.h:2:", "host/analysis/raw.cpp:1:",
            "host/batch: include cycle between p, q"]
    with tempfile.TemporaryDirectory() as root:
        for rel, text in tree.items():
            os.makedirs(os.path.join(root, os.path.dirname(rel)), exist_ok=True)
            with open(os.path.join(root, rel), "w") as f:
                f.write(text)
        got = violations(root)
    ok = len(got) == len(want) and all(any(g.startswith(w) for g in got) for w in want)
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
    print(f"{len(found)} breach(es) of the layer rules")
    return 1 if found else 0


sys.exit(main())
