#!/usr/bin/env python3
"""Layer resolution per DWR loop from a run directory: y_layer (probes), its change
against the previous loop, and how many cells along the cut line lie between the two
level crossings (s_hi, s_lo). The cut_<line>_loop-NNNN.csv files hold the cell
boundaries along the line followed by `per_piece` interior samples per cell (2p).
Usage: postprocess/layer_cells.py RUN_DIR [LINE] [P]   (LINE default "normal", P = 1)"""
import csv
import json
import sys


def cell_boundaries(path, per_piece):
    rows = list(csv.DictReader(open(path)))
    return [float(r["s"]) for k, r in enumerate(rows) if k % (per_piece + 1) == 0]


def cells_between(bounds, a, b):
    """Number of cells (fractional at both ends) between positions a < b."""
    n = 0.0
    for lo, hi in zip(bounds, bounds[1:]):
        overlap = max(0.0, min(hi, b) - max(lo, a))
        if hi > lo:
            n += overlap / (hi - lo)
    return n


def main():
    run = sys.argv[1]
    line = sys.argv[2] if len(sys.argv) > 2 else "normal"
    per_piece = 2 * (int(sys.argv[3]) if len(sys.argv) > 3 else 1)
    loops = json.load(open(f"{run}/summary.json"))["loops"]
    print("| loop | N_space | y_layer | change | s_hi | s_lo | cells between crossings | first cell |")
    print("|---|---|---|---|---|---|---|---|")
    prev = None
    for l in loops:
        p = l.get("probes", {})
        w, s_hi, s_lo = p.get("layer_width"), p.get("s_hi"), p.get("s_lo")
        if w is None or s_hi is None or s_lo is None:
            continue
        path = f"{run}/cut_{line}_loop-{l['loop']:04d}.csv"
        try:
            bounds = cell_boundaries(path, per_piece)
        except FileNotFoundError:
            continue
        n = cells_between(bounds, min(s_hi, s_lo), max(s_hi, s_lo))
        change = "" if prev is None else f"{abs(w - prev) / prev:.1%}"
        first = bounds[1] - bounds[0] if len(bounds) > 1 else float("nan")
        print(f"| {l['loop']} | {l['N_space']} | {w:.3e} | {change} | {s_hi:.2e} | {s_lo:.2e} | {n:.2f} | {first:.2e} |")
        prev = w


if __name__ == "__main__":
    main()
