#!/usr/bin/env python3
"""Side-by-side tables of scripts/bench_amg.sh (amg.csv): ILU(k) vs AMG inside the
Kronecker preconditioners vs UMFPACK.

Usage: amg_table.py amg.csv  -> prints Markdown and writes amg_table.md next to the CSV.

Per configuration (system, p, r, eps, refinements, aspect ratio) one row per solver:
mean / max Krylov iterations per slab, setup (factorization or preconditioner) s,
solve s per slab, amortized s per slab = setup / 10 + solve (10 slabs of
config/moving_hump.json), peak MB, and the ratio of the amortized time to that of ILU
(gmres+kronecker_presb): > 1 means slower than ILU. F = failed (stagnation, max
iterations or breakdown).
"""
import csv
import os
import sys
from collections import defaultdict

SLABS = 10
path = sys.argv[1]
rows = list(csv.DictReader(open(path)))


def f(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


def g(x, p=3):
    return "-" if x != x else f"{x:.{p}g}"


NAMES = {
    "-": "umfpack",
    "kronecker_presb": "presb+ilu",
    "kronecker_presb@amg": "presb+amg(ilu)",
    "kronecker_presb@amg-gs": "presb+amg(gs)",
    "kronecker@amg": "kron2n+amg(ilu)",
}
ORDER = list(NAMES.values())
groups = defaultdict(dict)
for r in rows:
    name = NAMES.get(r["preconditioner"], r["preconditioner"])
    r["per_slab"] = f(r["setup_s"]) / SLABS + f(r["solve_s_per_slab"])
    key = (r["system"], int(r["p"]), int(r["r"]), float(r["eps"]), int(r["refinements"]),
           int(r.get("aspect_ratio") or 1))
    groups[key][name] = r

lines = []


def out(s=""):
    print(s)
    lines.append(s)


out("| system | N_space | r | eps | aspect | solver | status | iters mean/max | setup s | "
    "solve s/slab | s/slab amortized | peak MB | time / ILU | peak / ILU |")
out("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for key in sorted(groups):
    g_ = groups[key]
    ilu = g_.get("presb+ilu")
    for name in ORDER + sorted(set(g_) - set(ORDER)):
        r = g_.get(name)
        if r is None:
            continue
        ok = r["status"] == "ok"
        its = "-" if name == "umfpack" else (
            f"{g(f(r['iters_mean']))}/{r['iters_max']}" if ok else "F")
        ratio = (r["per_slab"] / ilu["per_slab"]
                 if ok and ilu and ilu["status"] == "ok" else float("nan"))
        mratio = (f(r["peak_mb"]) / f(ilu["peak_mb"])
                  if ok and ilu and ilu["status"] == "ok" else float("nan"))
        out(f"| {key[0]} Q{key[1]} | {r['N_space']} | {key[2]} | {r['eps']} | {key[5]} | "
            f"{name} | {r['status']} | {its} | {g(f(r['setup_s']))} | "
            f"{g(f(r['solve_s_per_slab']))} | {g(r['per_slab'])} | {g(f(r['peak_mb']), 4)} | "
            f"{g(ratio)} | {g(mratio)} |")
with open(os.path.join(os.path.dirname(os.path.abspath(path)), "amg_table.md"), "w") as fh:
    fh.write("\n".join(lines) + "\n")
