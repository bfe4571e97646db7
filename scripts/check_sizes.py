#!/usr/bin/env python3
"""Checks the size rules of the code base: no source file over 500 lines, no function over 80.

Functions are found the way the code is laid out (Allman braces, .clang-format): a body opens
with '{' alone at column 0 after a signature that is not a namespace, struct, class, enum or
initializer, and closes with '}' at column 0. Usage: scripts/check_sizes.py [--max-file N]
[--max-function N] [paths...]; exit 1 if any rule is broken."""
import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DIRS = ["libs", "apps", "tests", "bench", "fuzz"]
NOT_FUNCTION = re.compile(r"^\s*(namespace|struct|class|enum|union|extern|public|private|protected)\b|=\s*$")


def sources(paths):
    for p in paths:
        for d, _, files in os.walk(p):
            if "/build" in d:
                continue
            for f in sorted(files):
                if f.endswith((".cpp", ".h", ".hpp")):
                    yield os.path.join(d, f)


def functions(lines):
    start = None
    for i, line in enumerate(lines):
        if line.rstrip() == "{" and start is None:
            j = i - 1
            while j >= 0 and not lines[j].strip():
                j -= 1
            sig = lines[j] if j >= 0 else ""
            if not NOT_FUNCTION.search(sig):
                start = (i, sig.strip())
        elif line.startswith("}") and start is not None:
            yield start[1], start[0] + 1, i - start[0] + 1
            start = None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-file", type=int, default=500)
    ap.add_argument("--max-function", type=int, default=80)
    ap.add_argument("paths", nargs="*")
    a = ap.parse_args()
    paths = a.paths or [os.path.join(ROOT, d) for d in DIRS]
    bad = 0
    for f in sources(paths):
        with open(f, encoding="utf-8") as fh:
            lines = fh.read().split("\n")
        rel = os.path.relpath(f, ROOT)
        if len(lines) - 1 > a.max_file:
            print(f"{rel}: {len(lines) - 1} lines (max {a.max_file})")
            bad += 1
        for sig, line, n in functions(lines):
            if n > a.max_function:
                print(f"{rel}:{line}: function of {n} lines (max {a.max_function}): {sig[:70]}")
                bad += 1
    print(f"check_sizes: {bad} violation(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
