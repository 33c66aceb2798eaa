#!/usr/bin/env python3
"""Table and chart of scripts/bench_error_control.sh.

Usage: error_control.py OUTDIR NAME [NAME ...]
Reads OUTDIR/NAME/loops.csv, OUTDIR/NAME/summary.json and OUTDIR/NAME.run (tolerance,
wall seconds, exit status); writes OUTDIR/error_control.csv (per problem and loop),
OUTDIR/error_control.md (per problem) and OUTDIR/error_control.png.
"""
import csv
import json
import math
import os
import sys

BAND = (0.8, 1.25)
WIDE = (0.7, 1.4)
N_TOT_MIN = 1e5


def number(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return math.nan


def load(out, name):
    rows = []
    with open(os.path.join(out, name, "loops.csv")) as f:
        for r in csv.DictReader(f):
            rows.append({k: number(v) for k, v in r.items()})
    with open(os.path.join(out, name, "summary.json")) as f:
        summary = json.load(f)
    tol, wall, status = open(os.path.join(out, name + ".run")).read().split()
    return rows, summary, float(tol), float(wall), int(status)


def main():
    out, names = sys.argv[1], sys.argv[2:]
    per_loop, per_problem = [], []
    for name in names:
        rows, summary, tol, wall, status = load(out, name)
        for r in rows:
            per_loop.append([name, int(r["loop"]), int(r["N_space"]), int(r["N_t"]),
                             int(r["N_tot"]), r["J_error"], r["eta_h"], r["eta_tau"],
                             r["eta_tauh"], r["eta_abs"], r["I_eff"]])
        last = rows[-1]
        big = [r for r in rows if r["N_tot"] >= N_TOT_MIN]
        ieff = [r["I_eff"] for r in big]
        outside = [int(r["loop"]) for r in big if not BAND[0] <= r["I_eff"] <= BAND[1]]
        wide = [int(r["loop"]) for r in big if not WIDE[0] <= r["I_eff"] <= WIDE[1]]
        eh, et = abs(last["eta_h"]), abs(last["eta_tau"])
        ratio = max(eh, et) / max(min(eh, et), 1e-300)
        balanced = ratio <= 10 or min(eh, et) < tol / 100
        err = abs(last["J_error"])
        stop = summary.get("stop_reason", summary.get("reason", ""))
        per_problem.append({
            "problem": name, "tolerance": tol, "stop": stop, "loops": int(last["loop"]),
            "N_tot": int(last["N_tot"]), "error": err, "error/TOL": err / tol,
            "eta_abs": last["eta_abs"], "I_eff_last": last["I_eff"],
            "I_eff_min": min(ieff) if ieff else math.nan,
            "I_eff_max": max(ieff) if ieff else math.nan,
            "loops_outside_band": " ".join(map(str, outside)) or "-",
            "ok": (status == 0 and stop == "tolerance" and err <= 1.25 * tol and
                   len(outside) <= 1 and not wide and balanced),
            "eta_h/eta_tau": eh / max(et, 1e-300), "wall_s": wall})
    with open(os.path.join(out, "error_control.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["problem", "loop", "N_space", "N_t", "N_tot", "J_error", "eta_h",
                    "eta_tau", "eta_tauh", "eta_abs", "I_eff"])
        w.writerows(per_loop)
    keys = list(per_problem[0].keys())
    fmt = lambda v: (f"{v:.3g}" if isinstance(v, float) else str(v))
    lines = ["| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
    lines += ["| " + " | ".join(fmt(p[k]) for k in keys) + " |" for p in per_problem]
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(out, "error_control.md"), "w") as f:
        f.write(table + "\n")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(matplotlib missing: no chart)")
        return
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.8))
    for name in names:
        rows = [r for r in per_loop if r[0] == name]
        a.semilogx([r[4] for r in rows], [r[10] for r in rows], "o-", ms=3, label=name)
    a.axhspan(*BAND, color="0.9")
    a.axvline(N_TOT_MIN, color="0.6", ls=":")
    a.set_ylim(0, 2)
    a.set_xlabel("N_tot (space-time DoFs)")
    a.set_ylabel("I_eff = |eta| / |J(u) - J(u_h)|")
    a.set_title("effectivity per loop (band 0.8-1.25 shaded)")
    a.legend(fontsize=7)
    for p in per_problem:
        b.loglog(p["tolerance"], p["error"], "o")
        b.annotate(p["problem"], (p["tolerance"], p["error"]), fontsize=7)
    lo = min(p["tolerance"] for p in per_problem) / 3
    hi = max(p["tolerance"] for p in per_problem) * 3
    b.loglog([lo, hi], [lo, hi], "k-", lw=0.8, label="error = TOL")
    b.loglog([lo, hi], [1.25 * lo, 1.25 * hi], "k--", lw=0.8, label="1.25 TOL")
    b.set_xlabel("tolerance")
    b.set_ylabel("|J(u) - J(u_h)| at the stop")
    b.set_title("error at the stop against the tolerance")
    b.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "error_control.png"), dpi=110)


if __name__ == "__main__":
    main()
