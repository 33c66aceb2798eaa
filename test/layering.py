#!/usr/bin/env python3
"""Module layering of lib/ (ctest layering).

Usage: layering.py ROOT

The modules in the order of README's "Design" list; a file of a module may include
headers of its own module and of modules before it, never of one after it. Also fails
when two headers under lib/ share a file name. Prints one line per finding.
"""
import collections
import glob
import os
import re
import sys

ORDER = ["base", "scene", "space", "time", "goal", "solver", "slab", "adaptivity", "io",
         "config", "study", "dwr"]


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    rank = {m: i for i, m in enumerate(ORDER)}
    findings = []
    names = collections.defaultdict(list)
    for path in sorted(glob.glob(os.path.join(root, "lib", "*", "*"))):
        module = os.path.basename(os.path.dirname(path))
        if not path.endswith((".h", ".cc")):
            continue
        if module not in rank:
            findings.append(f"{os.path.relpath(path, root)}: module '{module}' is not in "
                            "the layering order (test/layering.py, README 'Design')")
            continue
        if path.endswith(".h"):
            names[os.path.basename(path)].append(os.path.relpath(path, root))
        with open(path, encoding="utf-8") as f:
            for n, line in enumerate(f, 1):
                m = re.match(r'\s*#include "(\w+)/', line)
                if m and m.group(1) in rank and rank[m.group(1)] > rank[module]:
                    findings.append(f"{os.path.relpath(path, root)}:{n}: {module}/ includes "
                                    f"{m.group(1)}/, a module after it in the order")
    for name, paths in names.items():
        if len(paths) > 1:
            findings.append(f"header name {name} used twice: {', '.join(paths)}")
    for f in findings:
        print(f)
    print(f"layering: {len(findings)} findings")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
