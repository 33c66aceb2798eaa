#!/usr/bin/env python3
"""Table and chart of scripts/bench_error_control.sh.

Usage: error_control.py OUTDIR NAME [NAME ...]
Reads OUTDIR/NAME/loops.csv, OUTDIR/NAME/summary.json and OUTDIR/NAME.run (tolerance,
wall seconds, exit status); writes OUTDIR/error_control.csv (per problem and loop),
OUTDIR/error_control.md (per problem) and OUTDIR/error_control.png.

I_eff in loops.csv is |eta / (J(u) - J(u_h))|; the table also gives the signed ratio
eta / (J(u) - J(u_h)) of the combined goal (J(u) - J(u_h) = sum_i w_i (J_i(u) - J_i(u_h))
from summary.json's per-loop goals), negative where the estimate has the wrong sign, and
the loops where one goal's own estimate has the wrong sign while its error exceeds
the tolerance's share TOL/10 (columns err_<goal>, eta_<goal> of loops.csv). With
adaptivity.measure_time_error (EXTRA_SET) the per-loop CSV also has eta_h / err_h and
eta_tau / err_tau of the combined goal (err_tau = sum_i w_i err_time_<goal>, err_h =
err - err_tau), and the table names the loops outside the band whose two parts are each
within 0.7-1.4: there the parts' errors cancel in their sum.
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


def signed_error(loop):
    """sum_i w_i (J_i(u) - J_i(u_h)) of one loop of summary.json (NaN without J_exact)."""
    goals = loop.get("goals", {})
    if not goals:
        return math.nan
    return sum(number(g.get("weight")) * (number(g.get("J_exact")) - number(g.get("J_h")))
               for g in goals.values())


def signed_time_error(loop):
    """sum_i w_i err_tau,i (the goals' measured temporal errors, with
    adaptivity.measure_time_error; NaN without them)."""
    goals = loop.get("goals", {})
    if not goals:
        return math.nan
    return sum(number(g.get("weight")) * number(loop.get("err_time_" + n))
               for n, g in goals.items())


def wrong_sign_goals(row, tol, goals):
    """Goals whose own estimate has the wrong sign where |err| > |J| TOL/10 (goals: the
    loop's per-goal entries of summary.json)."""
    out = []
    for k in row:
        if k.startswith("err_") and not k.startswith(("err_time_", "err_tau")):
            g = k[4:]
            e, eta = row[k], row.get("eta_" + g, math.nan)
            if e * eta < 0 and abs(e) > 0.1 * tol * abs(number(goals.get(g, {}).get("J_h", 1.0))):
                out.append(g)
    return out


def space_time_parts(row, loop):
    """|eta_h,x| + |eta_h,y| and |eta_tau| as the tolerance's measure (parts) sums them: per
    goal, weighted by |w_i|, where every goal has its own parts in summary.json (loop);
    else the weighted goal's."""
    goals = loop.get("goals", {})
    if goals and all(loop.get("eta_tau_" + n) is not None for n in goals):
        w = {n: abs(number(g.get("weight"))) for n, g in goals.items()}
        space = sum(w[n] * (abs(number(loop.get("eta_hx_" + n))) +
                            abs(number(loop.get("eta_hy_" + n)))) for n in goals)
        time = sum(w[n] * abs(number(loop.get("eta_tau_" + n))) for n in goals)
        if math.isfinite(space) and math.isfinite(time):
            return space, time
    return abs(row["eta_h"]), abs(row["eta_tau"])


def main():
    out, names = sys.argv[1], sys.argv[2:]
    per_loop, per_problem = [], []
    for name in names:
        rows, summary, tol, wall, status = load(out, name)
        by_loop = {int(l["loop"]): l for l in summary.get("loops", [])}
        for r in rows:
            err = signed_error(by_loop.get(int(r["loop"]), {}))
            r["I_signed"] = r["eta_tauh"] / err if err else math.nan
            err_tau = signed_time_error(by_loop.get(int(r["loop"]), {}))
            r["I_tau"] = r["eta_tau"] / err_tau if err_tau else math.nan
            r["I_h"] = r["eta_h"] / (err - err_tau) if err != err_tau else math.nan
            per_loop.append([name, int(r["loop"]), int(r["N_space"]), int(r["N_t"]),
                             int(r["N_tot"]), r["J_error"], r["eta_h"], r["eta_tau"],
                             r["eta_tauh"], r["eta_abs"], r["I_eff"], r["I_signed"],
                             r["I_h"], r["I_tau"]])
        last = rows[-1]
        big = [r for r in rows if r["N_tot"] >= N_TOT_MIN]
        ieff = [r["I_signed"] for r in big]
        outside = [int(r["loop"]) for r in big if not BAND[0] <= r["I_signed"] <= BAND[1]]
        wide = [int(r["loop"]) for r in big if not WIDE[0] <= r["I_signed"] <= WIDE[1]]
        goals = lambda r: by_loop.get(int(r["loop"]), {}).get("goals", {})
        # loops outside the band whose time and space parts are each estimated within the
        # wide band: the parts' errors cancel in the sum (needs measure_time_error)
        cancel = [int(r["loop"]) for r in big if int(r["loop"]) in outside and
                  all(WIDE[0] <= r[k] <= WIDE[1] for k in ("I_h", "I_tau"))]
        wrong = [f'{int(r["loop"])}:{",".join(wrong_sign_goals(r, tol, goals(r)))}'
                 for r in big if wrong_sign_goals(r, tol, goals(r))]
        eh, et = space_time_parts(last, by_loop.get(int(last["loop"]), {}))
        ratio = max(eh, et) / max(min(eh, et), 1e-300)
        balanced = ratio <= 10 or min(eh, et) < tol / 100
        err = abs(last["J_error"])
        stop = summary.get("stop_reason", summary.get("reason", ""))
        per_problem.append({
            "problem": name, "tolerance": tol, "stop": stop, "loops": int(last["loop"]),
            "N_tot": int(last["N_tot"]), "error": err, "error/TOL": err / tol,
            "eta_abs": last["eta_abs"], "I_eff_last": last["I_signed"],
            "I_eff_min": min(ieff) if ieff else math.nan,
            "I_eff_max": max(ieff) if ieff else math.nan,
            "loops_outside_band": " ".join(map(str, outside)) or "-",
            "parts_in_band": " ".join(map(str, cancel)) or "-",
            "goal_sign_wrong": " ".join(wrong) or "-",
            "ok": (status == 0 and stop == "tolerance" and err <= 1.25 * tol and
                   len(outside) <= 1 and not wide and balanced),
            "eta_h/eta_tau": eh / max(et, 1e-300), "wall_s": wall})
    with open(os.path.join(out, "error_control.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["problem", "loop", "N_space", "N_t", "N_tot", "J_error", "eta_h",
                    "eta_tau", "eta_tauh", "eta_abs", "I_eff", "I_eff_signed", "I_h", "I_tau"])
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
        a.semilogx([r[4] for r in rows], [r[11] for r in rows], "o-", ms=3, label=name)
    a.axhspan(*BAND, color="0.9")
    a.axvline(N_TOT_MIN, color="0.6", ls=":")
    a.axhline(0, color="0.6", lw=0.8)
    a.set_ylim(-1, 2)
    a.set_xlabel("N_tot (space-time DoFs)")
    a.set_ylabel("I_eff = eta / (J(u) - J(u_h)), signed")
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
