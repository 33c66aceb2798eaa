#!/usr/bin/env python3
"""The two tables of doc/results.md "Convergence orders in time and space" from the
convergence.csv files that scripts/convergence_table.sh writes: the finest level's error
and observed orders of each convergence_{time_r*,space_p*} run against the expected ones,
and every level of convergence_moving_hump. Usage: convergence_table.py OUTDIR"""
import csv
import os
import sys

EXPECTED = {  # L2L2 / nodal orders of dG(r) in time, h^(p+1) in space (doc/method.md §2)
    "time_r0": "1 / 1", "time_r1": "2 / 3", "time_r2": "3 / 5", "time_r3": "4 / 7",
    "space_p1": "2", "space_p2": "3", "space_p3": "4", "space_p4": "5",
}


def rows(out, name):
    with open(os.path.join(out, "convergence_" + name, "convergence.csv")) as f:
        return list(csv.DictReader(f))


def main(out):
    print("| config | expected order (L2L2 / nodal) | finest level: N_tot | err_L2L2 | "
          "order_L2_T | order_nodal | order_L2L2 |")
    print("|---|---|---|---|---|---|---|")
    for name, expected in EXPECTED.items():
        last = rows(out, name)[-1]
        print(f"| convergence_{name} | {expected} | {int(float(last['N_tot']))} | "
              f"{float(last['err_L2L2']):.2e} | {float(last['order_L2_T']):.2f} | "
              f"{float(last['order_nodal']):.2f} | {float(last['order_L2L2']):.2f} |")
    print()
    print("| N_space | N_t | N_tot | err_L2_T | err_L2L2 | wall time (s) |")
    print("|---|---|---|---|---|---|")
    for r in rows(out, "moving_hump"):
        print(f"| {r['N_space']} | {r['N_t']} | {r['N_tot']} | {float(r['err_L2_T']):.3e} | "
              f"{float(r['err_L2L2']):.3e} | {float(r['wall_time']):.3g} |")


if __name__ == "__main__":
    main(sys.argv[1])
