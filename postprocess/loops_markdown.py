#!/usr/bin/python3
"""Print a DWR run's loops.csv as a Markdown table with the cumulative wall time.

Usage: loops_markdown.py DIR/loops.csv
"""
import csv
import sys


def fmt(v, kind):
    if v == "":
        return "–"
    x = float(v)
    return {"int": f"{int(x)}", "sci": f"{x:.2e}", "fix": f"{x:.2f}", "t": f"{x:.1f}"}[kind]


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    cols = [("loop", "int"), ("N_space", "int"), ("N_t", "int"), ("N_tot", "int"), ("J_error", "sci"),
            ("eta_hx", "sci"), ("eta_hy", "sci"), ("eta_tau", "sci"), ("I_eff", "fix"), ("ar_max", "int"),
            ("t_primal", "t"), ("t_adjoint", "t"), ("t_estimate", "t"), ("mem_peak", "int")]
    print("| " + " | ".join(c for c, _ in cols) + " | cumulative s |")
    print("|" + "---|" * (len(cols) + 1))
    total = 0.0
    for r in rows:
        total += sum(float(r[k] or 0) for k in ("t_primal", "t_adjoint", "t_estimate", "t_refine"))
        print("| " + " | ".join(fmt(r[c], k) for c, k in cols) + f" | {total:.0f} |")


if __name__ == "__main__":
    main()
