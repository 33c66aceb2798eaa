#!/usr/bin/env python3
"""The cell at a boundary point, loop by loop: its size along the outward normal and
along the boundary, its two directional indicators (normal and tangential) and the
rank of its total indicator among all cells, from the loop-NNNN.cells.csv files of a
DWR run (output.vtu_loops = 1). With the probes.csv of the run it also prints y_layer,
so that a stalled layer width can be traced to the cut the cell received.
Usage: postprocess/first_cell.py RUN_DIR [X Y]   (default: hemker's x_Gamma, normal
x/|x|, i.e. the outward normal of the unit circle)"""
import csv
import glob
import math
import re
import sys


def contains(poly, q):
    """poly: 4 vertices counter-clockwise."""
    for i in range(4):
        (ax, ay), (bx, by) = poly[i], poly[(i + 1) % 4]
        if (bx - ax) * (q[1] - ay) - (by - ay) * (q[0] - ax) < -1e-14:
            return False
    return True


def main():
    run = sys.argv[1]
    x = (float(sys.argv[2]), float(sys.argv[3])) if len(sys.argv) > 3 else (
        -2 ** -0.5, 2 ** -0.5)
    r = math.hypot(*x)
    n = (x[0] / r, x[1] / r)
    q = (x[0] + 1e-10 * n[0], x[1] + 1e-10 * n[1])
    layer = {}
    try:
        for row in csv.DictReader(open(f"{run}/probes.csv")):
            layer[int(row["loop"])] = float(row["layer_width"])
    except FileNotFoundError:
        pass
    print("| loop | N_cells | h_normal | h_tangential | eta normal | eta tangential "
          "| rank of the cell | y_layer | y_layer / h_normal |")
    print("|---|---|---|---|---|---|---|---|---|")
    for path in sorted(glob.glob(f"{run}/loop-*.cells.csv")):
        loop = int(re.search(r"loop-(\d+)\.cells", path).group(1))
        rows = list(csv.DictReader(open(path)))
        total = [abs(float(c["eta_hx"])) + abs(float(c["eta_hy"])) for c in rows]
        for k, c in enumerate(rows):
            # columns: vertices 0, 1, 3, 2 of the deal.II cell (counter-clockwise)
            poly = [(float(c[f"x{j}"]), float(c[f"y{j}"])) for j in range(4)]
            if not contains(poly, q):
                continue
            ex = (poly[1][0] - poly[0][0], poly[1][1] - poly[0][1])  # reference x
            ey = (poly[3][0] - poly[0][0], poly[3][1] - poly[0][1])  # reference y
            x_normal = abs(ex[0] * n[0] + ex[1] * n[1]) > abs(ey[0] * n[0] + ey[1] * n[1])
            e_n, e_t = (ex, ey) if x_normal else (ey, ex)
            eta_n = float(c["eta_hx" if x_normal else "eta_hy"])
            eta_t = float(c["eta_hy" if x_normal else "eta_hx"])
            rank = sum(t > total[k] for t in total) + 1
            h_n = math.hypot(*e_n)
            y = layer.get(loop, float("nan"))
            print(f"| {loop} | {len(rows)} | {h_n:.2e} | {math.hypot(*e_t):.2e} | "
                  f"{abs(eta_n):.2e} | {abs(eta_t):.2e} | {rank} | {y:.2e} | "
                  f"{y / h_n:.2f} |")
            break


if __name__ == "__main__":
    main()
