#!/usr/bin/env bash
# Krylov iteration counts of gmres + kronecker_presb on the moving hump primal slab
# system (Q1, SUPG, 3 slabs, tau = 0.05) over r = 0..3, eps = 1e-2..1e-8 and cell
# aspect ratios 1, 32, 1024 (BENCH_ANISO: every cell cut 0, 5, 10 more times in y; the
# base refinement is chosen so that N_space stays between 1.7e4 and 7.4e4), for each
# ILU(k) level in FILLS. Prints a Markdown table per level: mean iterations per
# (r, eps, aspect ratio), and the spread max/min over all of them (doc/results.md;
# the CSV of the last run is doc/bench_iteration_spread.csv).
# INNERS lists solver.inner_iterations values (0 = one ILU application per temporal
# mode block; k > 0 = up to k inner GMRES iterations to INNER_TOL, outer fgmres); the
# table then also gives the inner iterations per slab solve.
# Usage: scripts/bench_iteration_spread.sh [OUTDIR]
# Env: FILLS (default "1 2"), INNERS (default "0"), INNER_TOL (default 1e-2).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${ANISODWR_BUILD_DIR:-$ROOT/build}/bench/anisodwr_bench_solvers
OUT=${1:-$ROOT/results/bench_iteration_spread}
mkdir -p "$OUT"
CSV=$OUT/spread.csv
"$BIN" --header | sed 's/^/ilu_fill,/' >"$CSV"
for inner in ${INNERS:-0}; do
for fill in ${FILLS:-1 2}; do
  for spec in 0:8 5:5 10:3; do
    aniso=${spec%%:*} refs=${spec##*:}
    for r in 0 1 2 3; do
      for eps in 1e-2 1e-4 1e-6 1e-8; do
        krylov=gmres
        [ "$inner" -gt 0 ] && krylov=fgmres
        line=$(BENCH_ILU_FILL=$fill BENCH_ANISO=$aniso BENCH_INNER=$inner \
          BENCH_INNER_TOL=${INNER_TOL:-1e-2} "$BIN" primal 1 "$r" "$eps" "$refs" \
          $krylov+kronecker_presb 3 2>/dev/null || true)
        echo "$fill,$line" >>"$CSV"
      done
    done
  done
done
done
/usr/bin/python3 - "$CSV" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
for fill, inner in sorted({(r["ilu_fill"], r["inner_iterations"]) for r in rows}):
    same = [r for r in rows if r["ilu_fill"] == fill and r["inner_iterations"] == inner]
    sub = [r for r in same if r["status"] == "ok"]
    bad = [r for r in same if r["status"] != "ok"]
    what = "gmres" if inner == "0" else f"fgmres, inner GMRES up to {inner}"
    print(f"\nILU({fill}), {what}: mean outer iterations per slab solve"
          + ("" if inner == "0" else " / inner iterations / solve s per slab")
          + f" (status not ok: {len(bad)})\n")
    ars = sorted({r["aspect_ratio"] for r in sub}, key=float)
    print("| r | eps | " + " | ".join(f"AR {a} (N_space {next(x['N_space'] for x in sub if x['aspect_ratio'] == a)})" for a in ars) + " |")
    print("|---|---|" + "---|" * len(ars))
    for r in "0123":
        for eps in ["1e-2", "1e-4", "1e-6", "1e-8"]:
            cells = []
            for a in ars:
                m = [x for x in sub if x["r"] == r and x["eps"] == eps and x["aspect_ratio"] == a]
                if not m:
                    cells.append("-")
                elif inner == "0":
                    cells.append(m[0]["iters_mean"])
                else:
                    x = m[0]
                    cells.append(f'{float(x["iters_mean"]):.3g} / {float(x["inner_mean"]):.0f} / {float(x["solve_s_per_slab"]):.2f}')
            print(f"| {r} | {eps} | " + " | ".join(cells) + " |")
    it = [float(x["iters_mean"]) for x in sub]
    if it:
        print(f"\nspread max/min = {max(it):.1f}/{min(it):.1f} = {max(it)/min(it):.2f}")
    if inner != "0" and sub:
        inn = [float(x["inner_mean"]) for x in sub]
        print(f"inner iterations per solve: {min(inn):.0f} ... {max(inn):.0f}")
    ts = [float(x["solve_s_per_slab"]) for x in sub]
    if ts:
        print(f"solve time per slab: {min(ts):.3f} ... {max(ts):.3f} s, total {sum(ts):.2f} s")
PY
