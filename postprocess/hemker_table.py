#!/usr/bin/env python3
"""The per-goal table of a Hemker run (doc/results.md, "Hemker: refined as far as the
memory allows"): loops.csv and probes.csv of a run with one estimate per goal
(adaptivity.tolerance_measure = goals or per_goal_estimates = true) and goal.reference.

Usage: postprocess/hemker_table.py RESULTS_DIR [FIRST_LOOP]
Prints a Markdown table: N_space, J_1, e_1 = ref_1 - J_1, eta_1, eta_1/e_1, J_2,
eta_2/e_2, the layer width, under-/overshoot over the goals' domain of influence, the
tolerance measure max_i |eta_i| / |J_i| against the true max_i |e_i| / ref_i, and the
cumulative phase time and peak memory.
"""
import csv
import os
import sys

REF = {"u_xe1_I": 2.605, "u_xe2_I": 1.22e-3}


def main():
    d = sys.argv[1]
    first = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    loops = list(csv.DictReader(open(os.path.join(d, "loops.csv"))))
    probes = {p["loop"]: p for p in csv.DictReader(open(os.path.join(d, "probes.csv")))}
    print("| loop | N_space | J_1 | e_1 | η_1 | η_1/e_1 | J_2 | η_2/e_2 | layer width | "
          "under- / overshoot | max η_i/J_i | max e_i/ref_i | time (s) | peak MB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    t = 0.0
    for x in loops:
        t += sum(float(x[k]) for k in ("t_primal", "t_adjoint", "t_estimate", "t_refine"))
        if int(x["loop"]) < first:
            continue
        p = probes[x["loop"]]
        J = {g: float(p["J_" + g]) for g in REF}
        e = {g: float(x["err_" + g]) for g in REF}
        eta = {g: float(x["eta_" + g]) for g in REF}
        measure = max(abs(eta[g]) / abs(J[g]) for g in REF)
        true = max(abs(e[g]) / REF[g] for g in REF)
        g1, g2 = "u_xe1_I", "u_xe2_I"
        # empty where u_h(T) has no 0.1 and 0.9 crossings along the normal (coarse loops)
        layer = f"{float(p['layer_width']):.3e}" if p["layer_width"] else "–"
        print(f"| {x['loop']} | {int(float(x['N_space'])):,} | {J[g1]:.4f} | {e[g1]:+.4f} | "
              f"{eta[g1]:+.4f} | {eta[g1] / e[g1]:.2f} | {J[g2]:.4e} | "
              f"{eta[g2] / e[g2]:.2f} | {layer} | "
              f"{float(p['undershoot_goals']):.3f} / {float(p['overshoot_goals']):.3f} | "
              f"{measure:.4f} | {true:.4f} | {t:.0f} | {float(x['mem_peak']):.0f} |")


if __name__ == "__main__":
    main()
