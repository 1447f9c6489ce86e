#!/usr/bin/env python3
"""Every repository path the docs name exists: scans README.md and docs/*.md for paths under the
repository's folders (host/, kernels/, interface/, formats/, scripts/, tests/, docs/, bench/,
data/, cmake/, .ci/) in backticks, in fenced code blocks, as relative Markdown link targets and,
in running text, those that end in a file name with an extension (docs/mts.md), and prints FILE:LINE: path for each that names no file or folder; exits 1 if there is one.

A path with a glob (`host/render/render_evaluator.*`, `kernels/mts/*.cl`) must match something.
Not checked: placeholders (`data/audit/FILE`, `bench/results/<name>.txt`, `…`), anything not
under those folders (`build/...`, `/tmp/...`, `share/depthprec/...`: made by a build, a run or an
install), and a path given to -o or > (an output the command writes).

Usage: check_doc_paths.py [SOURCE_DIR]     checks SOURCE_DIR (default: this repository)
       check_doc_paths.py --self-test      checks that a missing path is found and a placeholder
                                           is not
"""
import glob
import os
import re
import sys
import tempfile

FOLDERS = ("host", "kernels", "interface", "formats", "scripts", "tests", "docs", "bench", "data",
           "cmake", ".ci")
# a path: one of the folders, then path characters (a glob's * and a placeholder's <> included)
PATH = re.compile(r"(?<![\w./-])(?:\./)?((?:" + "|".join(re.escape(f) for f in FOLDERS) +
                  r")/[\w.*<>{}…+-]*(?:/[\w.*<>{}…+-]*)*)")
BACKTICKS = re.compile(r"`([^`]+)`")
LINK = re.compile(r"\]\(([^)\s]+)\)")
# a component that stands for something: FILE, NAME.json, TARGET_fuzzer.cpp, <technique>, {a,b},
# …, ... (asked only of a path that does not exist, so README.md is a file)
PLACEHOLDER = re.compile(r"(?:^|[_.-])[A-Z][A-Z0-9]+(?:$|[_.-])|[<>{}…]|\.\.\.")
OUTPUT_FLAG = re.compile(r"(?:^|\s)(?:-o|--output|>|>>)\s*$")


def is_placeholder(path):
    return any(PLACEHOLDER.search(part) for part in path.split("/") if part)


def exists(root, path):
    path = path.rstrip("/")
    if "*" in path:
        return bool(glob.glob(os.path.join(root, path)))
    return os.path.exists(os.path.join(root, path))


def paths_in(text):
    """(path, written) for each repository path in text; written when it follows -o or >."""
    for m in PATH.finditer(text):
        path = m.group(1).rstrip(".,:;")
        yield path, bool(OUTPUT_FLAG.search(text[:m.start()]))


def doc_files(root):
    docs = sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    readme = os.path.join(root, "README.md")
    return ([readme] if os.path.exists(readme) else []) + docs


def broken(root):
    found = []
    for doc in doc_files(root):
        rel_doc = os.path.relpath(doc, root)
        fenced = False
        with open(doc, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                if line.lstrip().startswith("```"):
                    fenced = not fenced
                    continue
                spans = [line] if fenced else BACKTICKS.findall(line)
                named = [p for span in spans for p in paths_in(span)]
                if not fenced:
                    # running text: only file names, so that prose such as host/device is not one
                    plain = BACKTICKS.sub(" ", LINK.sub("] ", line))
                    named += [(p, w) for p, w in paths_in(plain)
                              if "." in p.rsplit("/", 1)[-1].lstrip(".")]
                if not fenced:
                    # a relative link target, relative to the doc; anchors and web links aside
                    for target in LINK.findall(line):
                        target = target.split("#")[0]
                        if not target or re.match(r"^[a-z]+:", target) or target.startswith("/"):
                            continue
                        full = os.path.normpath(os.path.join(os.path.dirname(rel_doc), target))
                        if not exists(root, full):
                            found.append(f"{rel_doc}:{number}: {target}")
                for path, written in named:
                    if not (written or exists(root, path) or is_placeholder(path)):
                        found.append(f"{rel_doc}:{number}: {path}")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as root:
        for path in ["host/audit/audit.cpp", "bench/run.sh", "docs/a.md", "data/audit/x.gltf"]:
            os.makedirs(os.path.join(root, os.path.dirname(path)), exist_ok=True)
            open(os.path.join(root, path), "w").close()
        with open(os.path.join(root, "README.md"), "w") as f:
            f.write("`host/audit/audit.cpp` and `host/audit/gone.cpp`, `host/audit/` and `host/mts/`\n"
                    "`bench/run.sh 3` writes `bench/results/<name>.txt`; `data/audit/FILE`\n"
                    "`host/audit/audit.*`, `host/audit/fixes.*`, `tests/NAME_x.cpp`; `build/depthprec`, `/tmp/x`\n"
                    "[a](docs/a.md#part), [b](docs/b.md), [web](https://example.com/docs/c.md)\n"
                    "```sh\nbench/run.sh -o bench/out.csv && scripts/gone.sh\n```\n"
                    "`depthprec table -o docs/new.md`\n"
                    "as docs/a.md says, not docs/c.md; host/device and host/audit/ in prose\n")
        got = broken(root)
        want = ["README.md:1: host/audit/gone.cpp", "README.md:1: host/mts/",
                "README.md:3: host/audit/fixes.*", "README.md:4: docs/b.md",
                "README.md:6: scripts/gone.sh", "README.md:9: docs/c.md"]
        ok = sorted(got) == sorted(want)
        print("\n".join(got))
        print("self-test " + ("passed" if ok else "FAILED: expected " + ", ".join(want)))
        return 0 if ok else 1


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    found = broken(root)
    for b in found:
        print(b)
    print(f"{len(found)} path(s) named in the docs that do not exist")
    return 1 if found else 0


sys.exit(main())
