#!/usr/bin/env python3
"""Checks the size rules of the code base: no source file over 500 lines, no function over 80.

Functions are found by a small C++ scanner, whatever the brace style or indentation:
  1. comments, string and character literals (raw strings too) and preprocessor lines are
     blanked out (line breaks kept, so line numbers stay);
  2. braces are tracked with a stack; at namespace or class scope the text before each '{'
     since the last ';', '{' or '}' of that scope (the "head") decides what the block is:
     - namespace, extern "C": transparent (what is inside is at namespace scope);
     - class, struct, union, enum (after an optional template<...>): class scope (member
       functions defined in the class body are functions);
     - a head that ends with ')' (plus const, noexcept, override, final, mutable, &, &&,
       -> return type, try), or a constructor's ') : member-initializers' list: a function
       body (test macros such as TEST(A, B) too; a lambda assigned at namespace scope as well);
     - anything else (brace initializers such as `x = {`, `int a{0}`): not a function;
  3. every brace inside a function body belongs to that function: control blocks, lambdas and
     initializer lists are counted in the enclosing function, never as functions of their own.
The length of a function is the number of lines from the line of its '{' to the line of its
'}', inclusive (for Allman braces: the body with its braces).

Usage: scripts/check_sizes.py [--max-file N] [--max-function N] [--allow FILE] [paths...]
       scripts/check_sizes.py --list FILE...   (every function found: line, length, name)
The allow-list (default scripts/size_allowlist.txt; '--allow ""' for none) holds violations
that are known and being fixed elsewhere, one per line, tab-separated:
    path<TAB>function<TAB>length<TAB>note      (function '<file>' for a file's line count)
An allow-listed violation passes only while it is not longer than its listed length; an entry
that no longer violates (or no longer exists) is reported as stale and fails the check, so the
list can only shrink. Exit 1 if any rule is broken or any entry is stale."""
import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DIRS = ["libs", "apps", "tests", "bench", "fuzz"]
DEFAULT_ALLOW = os.path.join(ROOT, "scripts", "size_allowlist.txt")


def sources(paths):
    for p in paths:
        if os.path.isfile(p):
            yield p
            continue
        for d, dirs, files in os.walk(p):
            dirs[:] = sorted(x for x in dirs if not x.startswith("build"))
            for f in sorted(files):
                if f.endswith((".cpp", ".h", ".hpp", ".cc")):
                    yield os.path.join(d, f)


def _blank(s):
    """Keeps the line breaks of s, replaces everything else by spaces."""
    return re.sub(r"[^\n]", " ", s)


_RAW = re.compile(r'(?:u8|u|U|L)?R"([^()\\ ]{0,16})\(')


def strip_code(text):
    """Comments, literals and preprocessor lines replaced by blanks (same length, same lines)."""
    out = []
    i, n = 0, len(text)
    line_start = True
    while i < n:
        c = text[i]
        if line_start and c in " \t":
            out.append(c)
            i += 1
            continue
        if line_start and c == "#":
            j = i
            while j < n:  # preprocessor line with its continuations
                k = text.find("\n", j)
                if k < 0:
                    k = n
                if text[k - 1] == "\\" and k < n:
                    j = k + 1
                    continue
                break
            out.append(_blank(text[i:k]))
            i = k
            continue
        line_start = c == "\n"
        if text.startswith("//", i):
            k = text.find("\n", i)
            k = n if k < 0 else k
            out.append(_blank(text[i:k]))
            i = k
        elif text.startswith("/*", i):
            k = text.find("*/", i + 2)
            k = n if k < 0 else k + 2
            out.append(_blank(text[i:k]))
            i = k
        elif c == '"' or (c in "uULR8" and _RAW.match(text, i)):
            m = _RAW.match(text, i)
            if m and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
                end = ")" + m.group(1) + '"'
                k = text.find(end, m.end())
                k = n if k < 0 else k + len(end)
            elif c == '"':
                k = i + 1
                while k < n and text[k] != '"' and text[k] != "\n":
                    k += 2 if text[k] == "\\" else 1
                k = min(k + 1, n)
            else:
                out.append(c)
                i += 1
                continue
            out.append('"' + _blank(text[i + 1 : k - 1]) + '"' if k - i >= 2 else _blank(text[i:k]))
            i = k
        elif c == "'":
            # A digit separator (1'000) is not a character literal.
            if i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum() and \
                    re.match(r"[0-9a-fA-FxXbB']", text[i - 1]):
                out.append(" ")
                i += 1
                continue
            k = i + 1
            while k < n and text[k] != "'" and text[k] != "\n":
                k += 2 if text[k] == "\\" else 1
            k = min(k + 1, n)
            out.append(_blank(text[i:k]))
            i = k
        else:
            out.append(c)
            i += 1
    return "".join(out)


_TEMPLATE = re.compile(r"^\s*template\s*<")
_ACCESS = re.compile(r"^\s*(public|private|protected)\s*:(?!:)")
_ATTR = re.compile(r"\[\[.*?\]\]")
_CLASS = re.compile(r"^\s*((typedef|static|inline|constexpr|export)\s+)*(class|struct|union|enum)\b")
_NAMESPACE = re.compile(r'^\s*((inline\s+)?namespace\b|extern\s*"[^"]*"\s*$)')
_FUNC_TAIL = re.compile(
    r"\)\s*(?:(?:const|volatile|noexcept(?:\s*\([^()]*\))?|override|final|mutable|try|&&|&)\s*"
    r"|->\s*[^;{}=()]*?)*$")
_LAMBDA = re.compile(r"\[[^\[\]]*\]\s*(\([^()]*\))?\s*(mutable\s*)?(->[^{}]*)?$")
_CTOR_INIT = re.compile(r"\)\s*(noexcept\s*)?:(?!:)")


def _drop_template(h):
    """h without a leading template<...> (nested angle brackets balanced)."""
    while _TEMPLATE.match(h):
        i = h.index("<")
        depth = 0
        for j in range(i, len(h)):
            if h[j] == "<":
                depth += 1
            elif h[j] == ">":
                depth -= 1
                if depth == 0:
                    h = h[j + 1 :]
                    break
        else:
            return h
    return h


def _squash_braces(head):
    """The head with the contents of nested braced initializers removed: 'm_b{b}' -> 'm_b{}'."""
    out, depth = [], 0
    for c in head:
        if c == "{":
            if depth == 0:
                out.append("{")
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                out.append("}")
        elif depth == 0:
            out.append(c)
    return "".join(out)


def classify(head):
    """What a '{' at namespace or class scope opens: 'namespace', 'class', 'function', 'other'."""
    h = _ATTR.sub(" ", _squash_braces(head))
    while _ACCESS.match(h):
        h = _ACCESS.sub("", h, count=1)
    h = _drop_template(h).strip()
    if _NAMESPACE.match(h):
        return "namespace"
    if _CLASS.match(h) and "(" not in h.split(":")[0]:
        return "class"
    if _LAMBDA.search(h):
        return "function"  # a lambda defined at namespace scope: measured as a function
    if "(" not in h or h.endswith("="):
        return "other"
    if _FUNC_TAIL.search(h):
        return "function"
    # A constructor whose member-initializer list ends with a braced initializer: m_b{b}.
    if _CTOR_INIT.search(h) and h.endswith("{}"):
        return "function"
    return "other"


def function_name(head):
    h = _ATTR.sub(" ", head)
    while _ACCESS.match(h):
        h = _ACCESS.sub("", h, count=1)
    h = re.sub(r"__attribute__\s*\(\((?:[^()]|\([^()]*\))*\)\)", " ", _squash_braces(h))
    h = " ".join(_drop_template(h).split())
    m = re.match(r"^(TEST\w*\s*\([^)]*\))", h)
    if m:
        return re.sub(r"\s+", " ", m.group(1))
    m = re.search(r"([\w:]+)\s*=\s*\[[^\[\]]*\]", h)  # a lambda assigned to a name
    lam = "operator" not in h and _LAMBDA.search(h)
    if m and lam:
        return m.group(1) + " (lambda)"
    if lam:
        return "lambda"
    m = None
    depth = 0
    for i, c in enumerate(h):  # the identifier before the first '(' outside <...>
        if c == "<":
            depth += 1
        elif c == ">":
            depth = max(0, depth - 1)
        elif c == "(" and depth == 0:
            if re.search(r"operator\s*$", h[:i]):
                i = h.index(")", i) + 1  # operator()
            m = re.search(r"(~?[\w:]*operator\s*\S+|[~\w:]+)\s*(?:=\s*\[[^\]]*\]\s*)?$",
                          h[:i].rstrip())
            if m:
                return m.group(1)
            m = re.search(r"([\w:]+)\s*=\s*\[", h[:i])
            return m.group(1) if m else h[:i].strip()[-60:]
    return h[:60]


def functions(text):
    """(name, first line, length in lines) of every function body in the text of one file."""
    code = strip_code(text)
    # One frame per open brace: [kind, start of the current head inside it, line of '{',
    # head before it, name of the class (class frames)].
    stack = [["namespace", 0, 0, "", ""]]
    line = 1
    found = []
    for i, c in enumerate(code):
        if c == "\n":
            line += 1
            continue
        frame = stack[-1]
        top = frame[0]
        measured = top in ("function", "inner")
        if c == "{":
            head = code[frame[1] : i]
            if measured:
                kind = "inner"
            elif top == "other":
                # inside a braced initializer at namespace scope: a lambda there (a table of
                # functions) is measured as a function of its own, the rest is initializer
                kind = "function" if _LAMBDA.search(_squash_braces(head)) else "inner"
            else:
                kind = classify(head)
            cls = ""
            if kind == "class":
                m = re.search(r"\b(?:class|struct|union|enum)\s+(?:class\s+|struct\s+)?(\w+)",
                              _drop_template(_squash_braces(head)))
                cls = m.group(1) if m else ""
            elif kind == "function" and top == "class" and frame[4]:
                cls = frame[4]
            stack.append([kind, i + 1, line, head, cls])
        elif c == "}":
            if len(stack) == 1:
                continue  # unbalanced: ignore
            kind, _, open_line, head, cls = stack.pop()
            if kind == "function":
                name = function_name(head)
                if cls and "::" not in name and not name.startswith("TEST"):
                    name = cls + "::" + name
                found.append((name, open_line, line - open_line + 1))
            if not (kind == "other" and stack[-1][0] in ("namespace", "class")):
                # (a braced initializer's head continues: a constructor's m_b{b} before its body)
                stack[-1][1] = i + 1
        elif c == ";" and not measured:
            frame[1] = i + 1
        elif c == "," and top == "other":
            frame[1] = i + 1
    found.sort(key=lambda f: f[1])
    return found


def read_allow(path):
    allow = {}
    if not path or (path == DEFAULT_ALLOW and not os.path.exists(path)):
        return allow
    with open(path, encoding="utf-8") as fh:
        for k, raw in enumerate(fh, 1):
            s = raw.rstrip("\n")
            if not s.strip() or s.lstrip().startswith("#"):
                continue
            parts = s.split("\t")
            if len(parts) < 4 or not parts[2].strip().isdigit():
                raise SystemExit(f"{path}:{k}: expected path<TAB>function<TAB>length<TAB>note")
            allow[(parts[0].strip(), parts[1].strip())] = (int(parts[2]), k)
    return allow


def check(paths, max_file, max_function, allow):
    """The violations as printable lines, and the allow-list entries used (by key)."""
    out, used, scanned = [], set(), set()

    def report(rel, what, n, limit, msg):
        key = (rel, what)
        if key in allow:
            used.add(key)
            if n <= allow[key][0]:
                return
            msg += f" (allow-listed at {allow[key][0]}: it grew)"
        out.append(msg)

    for f in sources(paths):
        with open(f, encoding="utf-8") as fh:
            text = fh.read()
        lines = text.split("\n")
        rel = os.path.relpath(os.path.abspath(f), ROOT)
        scanned.add(rel)
        if len(lines) - 1 > max_file:
            report(rel, "<file>", len(lines) - 1, max_file,
                   f"{rel}: {len(lines) - 1} lines (max {max_file})")
        for name, line, n in functions(text):
            if n > max_function:
                report(rel, name, n, max_function,
                       f"{rel}:{line}: function of {n} lines (max {max_function}): {name}")
    return out, used, scanned


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-file", type=int, default=500)
    ap.add_argument("--max-function", type=int, default=80)
    ap.add_argument("--allow", default=DEFAULT_ALLOW)
    ap.add_argument("--list", action="store_true", help="print every function found")
    ap.add_argument("paths", nargs="*")
    a = ap.parse_args()
    if a.list:
        for f in a.paths:
            with open(f, encoding="utf-8") as fh:
                for name, line, n in functions(fh.read()):
                    print(f"{f}:{line}\t{n}\t{name}")
        return 0
    paths = a.paths or [os.path.join(ROOT, d) for d in DIRS]
    allow = read_allow(a.allow)
    bad, used, scanned = check(paths, a.max_file, a.max_function, allow)
    for msg in bad:
        print(msg)
    # Stale: an entry of a scanned file that is no violation; on the whole tree also an entry
    # whose file is gone.
    stale = [k for k in allow if k not in used and (k[0] in scanned or not a.paths)]
    if stale:
        for k in sorted(stale, key=lambda k: allow[k][1]):
            print(f"{os.path.relpath(a.allow, ROOT)}:{allow[k][1]}: stale entry {k[0]} {k[1]}: "
                  "no longer a violation; delete the line")
    print(f"check_sizes: {len(bad)} violation(s), {len(used)} allow-listed, {len(stale)} stale")
    return 1 if bad or stale else 0


if __name__ == "__main__":
    sys.exit(main())
