#!/usr/bin/env python3
"""Turns the summary.json files of scripts/bench_slab.sh into bench_slab.csv and a
Markdown table (printed): per (r, N_space) the times with factorization reuse, and
the speed-up of reuse over refactorizing every slab."""
import csv
import glob
import json
import os
import sys

out = sys.argv[1]
runs = {}
for f in glob.glob(os.path.join(out, "*", "summary.json")):
    s = json.load(open(f))
    c, lv = s["config"], s["levels"][0]
    key = (c["discretization"]["r"], lv["N_space"])
    runs.setdefault(key, {})[c["solver"]["reuse_factorization"]] = (lv, s["peak_memory_mb"])

cols = ["r", "N_space", "N_t", "N_tot", "assemble_s", "factorize_s", "solve_per_slab_s",
        "primal_s", "peak_mem_MB", "primal_s_no_reuse", "reuse_speedup"]
rows = []
for (r, n), v in sorted(runs.items()):
    if True not in v:
        continue
    lv, mem = v[True]
    w = lv["wall_time"]
    row = [r, n, lv["N_t"], lv["N_tot"], w["assemble_spatial"] + w["assemble_slab"],
           w["factorize"], w["solve"] / lv["N_t"], w["total"], mem]
    if False in v:
        t_no = v[False][0]["wall_time"]["total"]
        row += [t_no, t_no / w["total"]]
    else:
        row += ["", ""]
    rows.append(row)

with open(os.path.join(out, "bench_slab.csv"), "w", newline="") as f:
    csv.writer(f).writerows([cols] + rows)

fmt = lambda x: f"{x:.3g}" if isinstance(x, float) else str(x)
print("| " + " | ".join(cols) + " |")
print("|" + "---|" * len(cols))
for row in rows:
    print("| " + " | ".join(fmt(x) for x in row) + " |")
