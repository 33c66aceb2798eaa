#!/usr/bin/env python3
"""Tables and chart of scripts/bench_solvers.sh (solvers.csv).

Usage: solver_table.py solvers.csv   -> prints Markdown, writes solver_table.md and
solver_chart.png next to the CSV.

Per slab time = setup / 10 + solve (setup amortized over the 10 slabs of
config/moving_hump.json; UMFPACK reuses its factorization, the iterative solvers their
preconditioner). Solver memory = peak RSS - RSS before the slab matrices were built.
Ratios are UMFPACK / iterative: > 1 means the iterative solver is faster / smaller.
"""
import csv
import os
import sys
from collections import defaultdict

SLABS = 10
path = sys.argv[1]
out_dir = os.path.dirname(os.path.abspath(path))
rows = list(csv.DictReader(open(path)))


def f(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


for r in rows:
    r["name"] = "umfpack" if r["solver"] == "-" else f"{r['solver']}+{r['preconditioner']}"
    r["per_slab"] = f(r["setup_s"]) / SLABS + f(r["solve_s_per_slab"])
    r["solver_mb"] = f(r["peak_mb"]) - f(r["base_mb"])
    r["key"] = (r["system"], r["p"], r["r"], r["eps"], r["refinements"])

direct = {r["key"]: r for r in rows if r["name"] == "umfpack" and r["status"] == "ok"}
for r in rows:
    d = direct.get(r["key"])
    ok = r["status"] == "ok" and d is not None
    r["speedup"] = d["per_slab"] / r["per_slab"] if ok else float("nan")
    r["mem_ratio"] = d["peak_mb"] and f(d["peak_mb"]) / f(r["peak_mb"]) if ok else float("nan")
    r["solver_mem_ratio"] = d["solver_mb"] / r["solver_mb"] if ok else float("nan")

lines = []


def out(s=""):
    print(s)
    lines.append(s)


def g(x, p=3):
    return "-" if x != x else f"{x:.{p}g}"


def table(cols, body):
    out("| " + " | ".join(cols) + " |")
    out("|" + "---|" * len(cols))
    for b in body:
        out("| " + " | ".join(str(c) for c in b) + " |")
    out()


def system_name(r):
    return f"{r['system']} Q{r['p']}"


# 1. Size sweep: r = 1, eps = 1e-6.
out("### Slab solvers versus N_space (r = 1, eps = 1e-6)")
out()
sweep = [r for r in rows if r["r"] == "1" and r["eps"] == "1e-6"]
sweep.sort(key=lambda r: (r["system"], int(r["p"]), int(r["N_space"] or 0), r["name"] != "umfpack", r["name"]))
seen = set()
body = []
for r in sweep:
    k = (r["key"], r["name"])
    if k in seen:
        continue
    seen.add(k)
    body.append([system_name(r), r["N_space"], r["N_slab"], r["name"], r["status"],
                 g(f(r["iters_mean"])), g(f(r["setup_s"])), g(f(r["solve_s_per_slab"])),
                 g(r["per_slab"]), g(f(r["peak_mb"]), 4), g(r["solver_mb"], 4),
                 g(r["speedup"]), g(r["mem_ratio"]), g(r["solver_mem_ratio"]), r["load1"][:4]])
table(["system", "N_space", "N_slab", "solver", "status", "iters", "setup s", "solve s/slab",
       "s/slab (amortized)", "peak MB", "solver MB", "time ratio", "peak ratio",
       "solver-MB ratio", "load"], body)

# 2. Iterations versus r and eps at fixed mesh.
for sys_p in sorted({(r["system"], r["p"], r["refinements"]) for r in rows
                     if r["eps"] in ("1e-2", "1e-8")}):
    sub = [r for r in rows if (r["system"], r["p"], r["refinements"]) == sys_p
           and r["name"] != "umfpack"]
    if not sub:
        continue
    n = sub[0]["N_space"]
    out(f"### Iterations ({sys_p[0]} Q{sys_p[1]}, N_space = {n}): rows solver, columns "
        "eps / r; F = failed (stagnation or max iterations), growth = r3 / r0 at eps 1e-6")
    out()
    epss = ["1e-2", "1e-4", "1e-6", "1e-8"]
    cols = ["solver"] + [f"{e} r{r}" for e in epss for r in range(4)] + ["growth r0->r3"]
    body = []
    it = {(r["name"], r["eps"], r["r"]): r for r in sub}
    for name in sorted({r["name"] for r in sub}):
        row = [name]
        for e in epss:
            for rr in range(4):
                x = it.get((name, e, str(rr)))
                row.append("" if x is None else ("F" if x["status"] != "ok" else g(f(x["iters_mean"]), 3)))
        a, b = it.get((name, "1e-6", "0")), it.get((name, "1e-6", "3"))
        growth = (f(b["iters_mean"]) / f(a["iters_mean"])
                  if a and b and a["status"] == b["status"] == "ok" and f(a["iters_mean"]) > 0
                  else float("nan"))
        row.append(g(growth))
        body.append(row)
    table(cols, body)

# 3. Time and memory ratios at the grid size, best iterative per configuration.
out("### Best iterative solver per configuration (amortized time ratio UMFPACK / best)")
out()
best = {}
for r in rows:
    if r["name"] == "umfpack" or r["status"] != "ok" or r["speedup"] != r["speedup"]:
        continue
    if r["key"] not in best or r["speedup"] > best[r["key"]]["speedup"]:
        best[r["key"]] = r
body = []
for k in sorted(best, key=lambda k: (k[0], int(k[1]), int(k[4]), int(k[2]), float(k[3]))):
    r = best[k]
    body.append([system_name(r), r["N_space"], r["r"], r["eps"], r["name"], g(f(r["iters_mean"])),
                 g(r["per_slab"]), g(direct[k]["per_slab"]), g(r["speedup"]), g(r["mem_ratio"]),
                 g(r["solver_mem_ratio"])])
table(["system", "N_space", "r", "eps", "best", "iters", "s/slab", "umfpack s/slab",
       "time ratio", "peak ratio", "solver-MB ratio"], body)

# 4. Failures.
out("### Failures")
out()
fails = [r for r in rows if r["status"] != "ok"]
counts = defaultdict(int)
for r in fails:
    counts[r["name"]] += 1
out("Failed runs per solver: " + ", ".join(f"{k}: {v}" for k, v in sorted(counts.items())))
out()
body = []
for r in fails:
    msg = r["message"].strip('"')
    i = msg.find("iterative solver")
    body.append([system_name(r), r["N_space"], r["r"], r["eps"], r["name"],
                 (msg[i:] if i >= 0 else msg)[:140]])
table(["system", "N_space", "r", "eps", "solver", "message"], body)

# 5. Crossover (r = 1, eps = 1e-6).
out("### Crossover (r = 1, eps = 1e-6): smallest N_space where the best iterative solver wins")
out()
body = []
for sp in sorted({(r["system"], r["p"]) for r in sweep}):
    sizes = sorted({int(r["N_space"]) for r in sweep if (r["system"], r["p"]) == sp and r["N_space"]})
    t_win = m_win = None
    for n in sizes:
        cand = [r for r in sweep if (r["system"], r["p"]) == sp and r["N_space"] == str(n)
                and r["name"] != "umfpack" and r["status"] == "ok"]
        if not cand:
            continue
        if t_win is None and max(c["speedup"] for c in cand) > 1:
            t_win = n
        if m_win is None and max(c["mem_ratio"] for c in cand) > 1:
            m_win = n
    body.append([f"{sp[0]} Q{sp[1]}", t_win or "not reached", m_win or "not reached",
                 max(sizes) if sizes else "-"])
table(["system", "time crossover N_space", "peak-memory crossover N_space",
       "largest N_space run"], body)

with open(os.path.join(out_dir, "solver_table.md"), "w") as fh:
    fh.write("\n".join(lines) + "\n")

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    ax[0].set_prop_cycle(color=plt.cm.tab20.colors)
    ax[1].set_prop_cycle(color=plt.cm.tab20.colors)
    ax[2].set_prop_cycle(color=plt.cm.tab20.colors)
    sel = [r for r in sweep if r["system"] == "primal" and r["p"] == "1" and r["status"] == "ok"]
    for name in sorted({r["name"] for r in sel}):
        pts = sorted((int(r["N_slab"]), r) for r in sel if r["name"] == name)
        x = [p[0] for p in pts]
        style = dict(color="k", lw=2.5, ls="--") if name == "umfpack" else dict(ls="-")
        ax[0].loglog(x, [p[1]["per_slab"] for p in pts], "o", label=name, **style)
        ax[1].loglog(x, [f(p[1]["peak_mb"]) for p in pts], "o", label=name, **style)
        if name != "umfpack":
            ax[2].semilogx(x, [f(p[1]["iters_mean"]) for p in pts], "o-", label=name)
    ax[0].set(xlabel="slab unknowns N_space (r+1)", ylabel="s per slab (setup/10 + solve)",
              title="primal Q1, r = 1, eps = 1e-6: time")
    ax[1].set(xlabel="slab unknowns", ylabel="peak MB (process)", title="peak memory")
    ax[2].set(xlabel="slab unknowns", ylabel="Krylov iterations per slab",
              title="iterations (tolerance 1e-10)")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
    ax[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "solver_chart.png"), dpi=110)
except ImportError:
    print("matplotlib missing: no chart")
