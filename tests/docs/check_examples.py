#!/usr/bin/env python3
"""The docs' examples print what they show: every fenced block of README.md and docs/*.md that
starts with a line `$ depthprec ARGS` (an example of real output) is run with the build's
depthprec, and its standard output must equal the block's lines after the command, byte for byte
but for trailing blanks. An example's output is a fact about the product as it is: when a change
moves it, the example is rerun and pasted again, and this says which.

Examples that take longer than a test should (`SLOW`, each named with its reason) are left out;
each is listed as skipped, so a reader sees what was not run.

Usage: check_examples.py DEPTHPREC [SOURCE_DIR]   runs the examples (default: this repository)
       check_examples.py --self-test               checks that a changed output is found
"""
import difflib
import glob
import os
import shlex
import subprocess
import sys
import tempfile

# Commands whose examples are not run here, by the start of their arguments, and why.
SLOW = {
    "advise --range": "about 30 s on 2 cores (bench/command_figures.sh: advise_separation)",
}


def examples(path):
    """(line number, arguments, expected output lines) of each example block in a Markdown file."""
    out = []
    lines = open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i].startswith("```") and i + 1 < len(lines) and \
                lines[i + 1].startswith("$ depthprec "):
            start = i + 1
            j = start + 1
            while j < len(lines) and not lines[j].startswith("```"):
                j += 1
            out.append((start + 1, lines[start][len("$ depthprec "):], lines[start + 1:j]))
            i = j
        i += 1
    return out


def normalise(lines):
    text = [line.rstrip() for line in lines]
    while text and not text[-1]:
        text.pop()
    return text


def check(exe, root):
    files = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    exe = os.path.abspath(exe)
    failures, ran = 0, 0
    for path in files:
        for line, args, expected in examples(path):
            where = f"{os.path.relpath(path, root)}:{line}"
            slow = next((why for start, why in SLOW.items() if args.startswith(start)), None)
            if slow:
                print(f"{where}: skipped, {slow}: depthprec {args}")
                continue
            run = subprocess.run([exe] + shlex.split(args), cwd=root, capture_output=True,
                                 text=True)
            ran += 1
            got = normalise(run.stdout.split("\n"))
            if run.returncode != 0 or got != normalise(expected):
                failures += 1
                print(f"{where}: depthprec {args}: exit {run.returncode}; the output differs from "
                      "the example (--- example, +++ now):")
                sys.stdout.writelines(d + "\n" for d in difflib.unified_diff(
                    normalise(expected), got, "example", "now", lineterm=""))
                if run.stderr:
                    print(run.stderr.rstrip())
    print(f"{ran} example(s) run, {failures} differ")
    return 1 if failures or ran == 0 else 0


def self_test():
    with tempfile.TemporaryDirectory() as root:
        os.mkdir(os.path.join(root, "docs"))
        exe = os.path.join(root, "fake")
        with open(exe, "w") as f:
            f.write("#!/bin/sh\necho \"$@\"\n")
        os.chmod(exe, 0o755)
        with open(os.path.join(root, "README.md"), "w") as f:
            f.write("```text\n$ depthprec say hello\nsay hello\n```\n")
        if check(exe, root) != 0:
            print("self-test: a matching example was reported")
            return 1
        with open(os.path.join(root, "docs", "x.md"), "w") as f:
            f.write("```text\n$ depthprec say goodbye\nsay hello\n```\n")
        if check(exe, root) != 1:
            print("self-test: a changed output was not found")
            return 1
    print("self-test passed")
    return 0


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] == "--self-test":
        sys.exit(self_test())
    if len(sys.argv) not in (2, 3):
        print(__doc__)
        sys.exit(2)
    sys.exit(check(sys.argv[1], sys.argv[2] if len(sys.argv) == 3 else
                   os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))))
