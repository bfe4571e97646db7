#!/usr/bin/env python3
"""Self-test of scripts/check_sizes.py (ctest SizeCheckSelfTest).

1. The fixture check_sizes_fixture.cpp.in announces every function with a marker comment
   "//@ NAME LENGTH" before it; the checker must find exactly these functions, in this order,
   with these lengths (Allman, K&R, one-line, members in class bodies, a constructor with a
   braced member initializer, lambdas inside a function, braces in comments and literals,
   templates, extern "C", a test macro, a lambda at namespace scope), and nothing else
   (namespaces, classes, enums, initializers).
2. The rule and the allow-list: the 87-line function is a violation at the default limit;
   allow-listed at 87 it passes; allow-listed at 86 it fails (it grew); an allow-listed entry
   that does not violate is reported as stale and fails."""
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
CHECKER = os.path.join(ROOT, "scripts", "check_sizes.py")
FIXTURE = os.path.join(HERE, "check_sizes_fixture.cpp.in")

sys.path.insert(0, os.path.join(ROOT, "scripts"))
import check_sizes  # noqa: E402

failures = []


def expect(cond, what):
    print(("ok    " if cond else "FAIL  ") + what)
    if not cond:
        failures.append(what)


text = open(FIXTURE, encoding="utf-8").read()
want = [(m.group(1), int(m.group(2)))
        for m in re.finditer(r"^[ \t]*//@ (.+) (\d+)$", text, re.MULTILINE)]
got = [(name, n) for name, _, n in check_sizes.functions(text)]
expect(len(want) == 15, f"the fixture announces 15 functions (found {len(want)} markers)")
for i in range(max(len(want), len(got))):
    w = want[i] if i < len(want) else None
    g = got[i] if i < len(got) else None
    expect(w == g, f"function {i + 1}: expected {w}, found {g}")


def run(allow_lines, *args):
    with tempfile.NamedTemporaryFile("w", suffix=".txt", delete=False) as fh:
        fh.write("".join(line + "\n" for line in allow_lines))
        allow = fh.name
    try:
        r = subprocess.run([sys.executable, CHECKER, "--allow", allow, *args, FIXTURE],
                           capture_output=True, text=True)
    finally:
        os.unlink(allow)
    return r.returncode, r.stdout + r.stderr


rel = os.path.relpath(FIXTURE, ROOT)
code, out = run([])
expect(code == 1 and "function of 87 lines (max 80): CLong::veryLong" in out,
       "the 87-line function violates the 80-line rule: " + out.strip().replace("\n", " | "))
code, out = run([], "--max-function", "87")
expect(code == 0, "at --max-function 87 it passes (the boundary is inclusive)")
code, out = run([], "--max-function", "86")
expect(code == 1, "at --max-function 86 it fails")
code, out = run([f"{rel}\tCLong::veryLong\t87\tbeing split in branch core"])
expect(code == 0 and "1 allow-listed" in out, "allow-listed at its length it passes: " + out.strip())
code, out = run([f"{rel}\tCLong::veryLong\t86\tbeing split in branch core"])
expect(code == 1 and "it grew" in out, "allow-listed at 86 it fails as grown: " + out.strip())
code, out = run([f"{rel}\tCLong::veryLong\t87\tbeing split in branch core",
                 f"{rel}\tCWidget::size\t90\tbeing split in branch core"])
expect(code == 1 and "stale entry" in out and "CWidget::size" in out,
       "an allow-listed entry that does not violate is stale and fails: " + out.strip())
code, out = run([f"{rel}\tveryLong\t87"])
expect(code != 0 and "expected path" in (out + ""), "a malformed allow-list line is an error")

print(f"test_check_sizes: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
