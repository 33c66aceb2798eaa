#!/usr/bin/env python3
"""Table and chart of marking variants (scripts/bench_marking.sh).

Usage: marking_table.py OUTDIR VARIANT... ; reads OUTDIR/VARIANT/{loops,probes}.csv,
writes OUTDIR/marking.csv, OUTDIR/marking.md and OUTDIR/marking.png.
"""
import csv
import sys


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    out, variants = sys.argv[1], sys.argv[2:]
    rows = []
    for v in variants:
        loops, probes = read(f"{out}/{v}/loops.csv"), read(f"{out}/{v}/probes.csv")
        prev = None
        for l, p in zip(loops, probes):
            n = float(l["N_space"])
            y = float(p["layer_width"] or "nan")  # empty: no 0.9/0.1 crossing
            rows.append({
                "variant": v, "loop": int(l["loop"]), "N_space": int(n),
                "growth": f"{n / prev:.2f}" if prev else "",
                "J_1": f"{float(p['J_u_xe1_I']):.4f}", "J_2": f"{float(p['J_u_xe2_I']):.4f}",
                "y_layer": f"{y:.3e}", "y_layer*N_space": f"{y * n:.1f}",
                "ar_max": f"{float(l['ar_max']):.0f}",
                "marked_x": l["marked_x"], "marked_y": l["marked_y"],
                "marked_xy": l["marked_xy"], "closure": l["closure"],
                "t_loop": f"{sum(float(l[k]) for k in ('t_primal', 't_adjoint', 't_estimate', 't_refine')):.1f}",
            })
            prev = n
    keys = list(rows[0].keys())
    with open(f"{out}/marking.csv", "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        w.writerows(rows)
    with open(f"{out}/marking.md", "w") as f:
        f.write("| " + " | ".join(keys) + " |\n|" + "---|" * len(keys) + "\n")
        for r in rows:
            f.write("| " + " | ".join(str(r[k]) for k in keys) + " |\n")
    print(open(f"{out}/marking.md").read())
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no chart")
        return
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for v in variants:
        rs = [r for r in rows if r["variant"] == v]
        n = [r["N_space"] for r in rs]
        ax[0].loglog(n, [float(r["y_layer"]) for r in rs], "o-", label=v)
        ax[1].semilogx(n, [float(r["J_1"]) for r in rs], "o-", label=v)
    ax[0].set_xlabel("N_space")
    ax[0].set_ylabel("y_layer at x_Γ")
    ax[1].set_xlabel("N_space")
    ax[1].set_ylabel("J_1 = ∫ u(x_e1, t) dt")
    for a in ax:
        a.grid(True, which="both", alpha=0.3)
    ax[0].legend()
    fig.suptitle("hemker: marking strategies (θ_h = 1/3 of the cells, bulk_θ: θ of the "
                 "summed indicators; 36 slabs, cG(1)-dG(0))")
    fig.tight_layout()
    fig.savefig(f"{out}/marking.png", dpi=110)


if __name__ == "__main__":
    main()
