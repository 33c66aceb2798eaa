#!/usr/bin/env python3
"""Documentation consistency (ctest docs_consistent).

Usage: docs_consistent.py ROOT

Fails (exit 1, one line per finding) when
- a file under doc/ is neither linked nor named from README.md or a document linked from
  it (transitively);
- a config in config/ is named in none of them;
- README's Results section states a number (decimals, powers of ten, thousands with
  commas) that appears in no linked reference document (the tables it is taken from;
  doc/history.md does not count);
- a reference document (README.md and the linked docs) uses history wording ("no longer",
  "as before", "the old ...", "the build before", "previous build", "(before)", ...):
  the reference describes what the program does, not how it changed.
"""
import os
import re
import sys

HISTORY = [r"\bno longer\b", r"\bas before\b", r"\bthe old (build|binary|model|code)\b",
           r"\bold binary\b", r"\bearlier build\b", r"\bthe build before\b",
           r"\bprevious (build|session|version)\b", r"\(before\)", r"\bused to be\b",
           r"\bis now\b", r"\bare now\b", r"\bnow (uses|gives|takes|runs)\b"]
NUMBER = re.compile(r"(?<![\w.])(?:\d+\.\d+(?:e[-+]?\d+)?|\d+e[-+]?\d+|\d{1,3}(?:,\d{3})+)(?![\w])")
BRACES = re.compile(r"([\w./-]*)\{([\w,]+)\}([\w./-]*)")
LINK = re.compile(r"\]\(([^)#\s]+)(?:#[^)]*)?\)")


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def linked_docs(root):
    """README.md and the local .md files reachable from it by links."""
    seen, todo = set(), [os.path.join(root, "README.md")]
    while todo:
        path = os.path.normpath(todo.pop())
        if path in seen or not os.path.isfile(path):
            continue
        seen.add(path)
        for target in LINK.findall(read(path)):
            if "://" in target:
                continue
            dest = os.path.normpath(os.path.join(os.path.dirname(path), target))
            if dest.endswith(".md"):
                todo.append(dest)
    return seen


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    docs = linked_docs(root)
    text = {p: read(p) for p in docs}
    everything = "\n".join(text.values())
    # names written with braces, e.g. convergence_space_p{1,2,3,4}.json
    everything += "\n" + "\n".join(
        m.group(1) + alt + m.group(3) for m in BRACES.finditer(everything)
        for alt in m.group(2).split(","))
    problems = []

    for d, _, files in os.walk(os.path.join(root, "doc")):
        for f in files:
            path = os.path.normpath(os.path.join(d, f))
            rel = os.path.relpath(path, root)
            if path in docs:
                continue
            if f not in everything:
                problems.append(f"{rel}: not linked or named from README.md or a linked doc")

    for f in sorted(os.listdir(os.path.join(root, "config"))):
        if f.endswith(".json") and f not in everything:
            problems.append(f"config/{f}: named in no doc (README.md or a linked doc)")

    readme = text[os.path.join(root, "README.md")]
    results = re.search(r"^## Results\n(.*?)^## ", readme, re.S | re.M)
    if not results:
        problems.append("README.md: no '## Results' section")
    else:
        others = "\n".join(t for p, t in text.items()
                           if not p.endswith(("README.md", "history.md")))
        known = set(NUMBER.findall(others))
        for n, line in enumerate(results.group(1).splitlines()):
            if not line.startswith("|"):
                continue
            for num in NUMBER.findall(line):
                if num not in known:
                    problems.append(f"README.md Results: {num} appears in no linked doc's table "
                                    f"(line: {line[:60]}...)")

    for p, t in text.items():
        if p.endswith("history.md"):
            continue
        for i, line in enumerate(t.splitlines(), 1):
            for pat in HISTORY:
                m = re.search(pat, line, re.I)
                if m:
                    problems.append(f"{os.path.relpath(p, root)}:{i}: history wording "
                                    f"'{m.group(0)}'")
    for p in problems:
        print(p)
    print(f"docs_consistent: {len(docs)} linked docs, {len(problems)} findings")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
