#!/usr/bin/python3
"""Compare DWR runs by the work needed for a given accuracy.

Usage: compare_loops.py DIR MODE [MODE ...]
Reads DIR/MODE/loops.csv for each mode; for each J-error level (powers of 10^(1/2)
between the largest error every run reached after its first loop and the smallest
error the first two runs both reached; a run that never got there shows nan) it interpolates log N_space against log J_error between
consecutive loops and prints N_space per mode and the ratio to the first mode.
Writes DIR/anisotropy.csv.
"""
import csv
import math
import sys


def read(path):
    with open(path) as f:
        return [{k: float(v) if v else math.nan for k, v in r.items()} for r in csv.DictReader(f)]


def dofs_for(rows, target):
    """Smallest N_space at which the run's J error drops to target (log-log interpolation)."""
    best = math.nan
    for a, b in zip(rows, rows[1:]):
        ea, eb = a["J_error"], b["J_error"]
        if ea > target >= eb and ea > 0 and eb > 0:
            s = (math.log(target) - math.log(ea)) / (math.log(eb) - math.log(ea))
            best = min(best if math.isfinite(best) else math.inf, math.exp(math.log(a["N_space"]) + s * (math.log(b["N_space"]) - math.log(a["N_space"]))))
    if not math.isfinite(best) and rows and rows[0]["J_error"] <= target:
        best = rows[0]["N_space"]
    return best


def main():
    out, modes = sys.argv[1], sys.argv[2:]
    runs = {m: read(f"{out}/{m}/loops.csv") for m in modes}
    hi = min(max(r["J_error"] for r in rows[1:]) for rows in runs.values())
    # down to the smallest error both of the first two runs reached (others: nan)
    lo = max(min(r["J_error"] for r in runs[m]) for m in modes[:2])
    levels = []
    k = math.floor(2 * math.log10(hi))
    while 10 ** (k / 2) >= lo:
        levels.append(10 ** (k / 2))
        k -= 1
    header = ["J_error"] + [f"N_space_{m}" for m in modes] + [f"ratio_{m}/{modes[0]}" for m in modes[1:]]
    print(" ".join(f"{h:>22}" for h in header))
    with open(f"{out}/anisotropy.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for e in levels:
            n = [dofs_for(runs[m], e) for m in modes]
            ratios = [x / n[0] if math.isfinite(x) and math.isfinite(n[0]) else math.nan for x in n[1:]]
            row = [e] + n + ratios
            w.writerow([f"{v:.4g}" for v in row])
            print(" ".join(f"{v:>22.4g}" for v in row))


if __name__ == "__main__":
    main()
