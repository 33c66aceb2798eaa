#!/usr/bin/python3
"""Tables of the stability study (scripts/stability_study.sh).

Reads every run directory OUTDIR/<scene>_<variant>/ (loops.csv, probes.csv, summary.json),
prints two Markdown tables and writes OUTDIR/stability.csv:
  1. per run, its last loop: N_space, N_tot, J error (against the exact solution, or
     goal.reference: hemker's weighted relative error), the J values where the error is
     not against an exact solution,
     overshoot / undershoot (domain and strip), max aspect ratio, cumulative run time;
  2. the uniform-mesh runs side by side per mesh level (equal DoFs): undershoot and
     overshoot for delta0 = 0 (Galerkin), 0.1 and 1.
Usage: stability_table.py OUTDIR
"""
import csv
import json
import math
import os
import sys


def read(path):
    with open(path) as f:
        return [{k: (float(v) if v else math.nan) for k, v in r.items()} for r in csv.DictReader(f)]


def sci(v):
    return "–" if v != v else f"{v:.2e}"


def main(out):
    runs = sorted(d for d in os.listdir(out) if os.path.isfile(os.path.join(out, d, "probes.csv")))
    rows, uniform = [], {}
    for d in runs:
        scene, _, variant = d.partition("_")
        if d.startswith("moving_hump_"):
            scene, variant = "moving_hump", d[len("moving_hump_"):]
        loops = read(os.path.join(out, d, "loops.csv"))
        probes = read(os.path.join(out, d, "probes.csv"))
        if not loops:
            continue
        with open(os.path.join(out, d, "summary.json")) as f:
            summary = json.load(f)
        last, p = loops[-1], probes[-1]
        goals = [k for k in p if k.startswith("J_")]
        total = sum(sum(r.get(k) or 0 for k in ("t_primal", "t_adjoint", "t_estimate", "t_refine"))
                    for r in loops)
        rows.append({"scene": scene, "variant": variant, "loops": int(last["loop"]),
                     "N_space": int(last["N_space"]), "N_tot": int(last["N_tot"]),
                     "J_error": last["J_error"], "J": " / ".join(f"{p[g]:.5f}" for g in goals),
                     "exact": summary.get("error_reference") == "exact",
                     "overshoot": p["overshoot"], "undershoot": p["undershoot"],
                     "overshoot_strip": p["overshoot_strip"], "undershoot_strip": p["undershoot_strip"],
                     "layer_width": p["layer_width"], "ar_max": last["ar_max"], "time_s": total,
                     "status": summary.get("status", "")[:60]})
        if variant.startswith("uniform_delta"):
            for r in probes:
                uniform.setdefault((scene, int(r["N_space"])), {})[variant[len("uniform_delta"):]] = r
    cols = list(rows[0].keys()) if rows else []
    with open(os.path.join(out, "stability.csv"), "w") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        w.writerows(rows)
    print("| scene | variant | loops | N_space | N_tot | J error | J values | over | under | over strip | under strip | y_layer | ar_max | time s |")
    print("|" + "---|" * 14)
    for r in rows:
        print(f"| {r['scene']} | {r['variant']} | {r['loops']} | {r['N_space']} | {r['N_tot']} | {sci(r['J_error'])} "
              f"| {'–' if r['exact'] else r['J']} | {sci(r['overshoot'])} | {sci(r['undershoot'])} "
              f"| {sci(r['overshoot_strip'])} | {sci(r['undershoot_strip'])} | {sci(r['layer_width'])} "
              f"| {r['ar_max']:.0f} | {r['time_s']:.1f} |")
    if uniform:
        print("\nUniform meshes (equal DoFs): undershoot / overshoot of u_h(T)\n")
        deltas = ["0", "0.1", "1"]
        print("| scene | N_space | " + " | ".join(f"delta0 = {d}" for d in deltas) + " |")
        print("|" + "---|" * (2 + len(deltas)))
        for (scene, n), by in sorted(uniform.items()):
            cells = [f"{sci(by[d]['undershoot'])} / {sci(by[d]['overshoot'])}" if d in by else "–" for d in deltas]
            print(f"| {scene} | {n} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "results/stability")
