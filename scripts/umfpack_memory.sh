#!/usr/bin/env bash
# UMFPACK's own memory figures on the slab matrices of DWR runs (doc/results.md,
# "UMFPACK's memory and the `auto` rule"): the first primal and adjoint slab matrix of
# the given loops (scripts/bench_mtx.sh with anisodwr's own UMFPACK wrapper, no iterative
# refinement), then a table of n, m = r + 1, UMFPACK's predicted peak after its symbolic
# analysis, its actual peak and factor size after the numeric factorization, the fit
# 150 (Q1) / 200 (Q2 and up) bytes n log2 n, and the peak per unknown.
# Writes OUT/bench_mtx.csv and OUT/umfpack_memory.md. About 2 minutes on 2 cores.
# Usage: scripts/umfpack_memory.sh [OUT]
# Env: CASES (default "hemker_count:13 moving_hump_p1:12 moving_hump_p1:13").
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${1:-$ROOT/results/umfpack_memory}
CASES=${CASES:-"hemker_count:13 moving_hump_p1:12 moving_hump_p1:13"} SOLVERS=umfpack_own \
  "$ROOT/scripts/bench_mtx.sh" "$OUT" >/dev/null
/usr/bin/python3 - "$OUT/bench_mtx.csv" "$ROOT/config" <<'PY' | tee "$OUT/umfpack_memory.md"
import csv, json, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("| scene, loop, matrix | n | m | symbolic bound MB | peak MB | factors MB | n·log n fit MB | peak bytes per unknown |")
print("|---|---|---|---|---|---|---|---|")
for r in rows:
    if not r["umf_peak_mb"]:
        print(f'| {r["scene"]} {r["loop"]}, {r["problem"]} | failed | | | | | | |')
        continue
    cfg = json.load(open(f'{sys.argv[2]}/{r["scene"]}.json'))
    p, deg = cfg["discretization"]["p"], cfg["adaptivity"].get("adjoint_degree", 0)
    degree = p if r["problem"] == "primal" else (deg or p + 1)
    n = int(r["unknowns"])
    m = cfg["discretization"]["r"] + 1
    fit = (150 if degree == 1 else 200) * n * math.log2(n) / 2**20
    peak = float(r["umf_peak_mb"])
    print(f'| {r["scene"]} {r["loop"]}, {r["problem"]} Q{degree} | {n:,} | {m} | {float(r["umf_bound_mb"]):,.1f} | '
          f'{peak:,.1f} | {float(r["umf_factors_mb"]):,.1f} | {fit:,.1f} | {peak * 2**20 / n:,.0f} |')
PY
