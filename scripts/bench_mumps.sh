#!/usr/bin/env bash
# One slab matrix solved directly: UMFPACK (one process) against MUMPS through PETSc on
# 1 and 2 MPI ranks (bench/bench_mumps.cc), each configuration in its own process(es):
# build, factorization (+ first solve), solve per right-hand side, peak RSS per rank and
# summed. Prints a Markdown table with the ratios against UMFPACK.
# Usage: scripts/bench_mumps.sh [OUTDIR]   Env: SIZES = "p:r:refinements ..."
# (default "1:1:8 1:1:9 2:1:8 1:2:8"), RANKS (default "1 2").
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${ANISODWR_BUILD_DIR:-$ROOT/build}/bench/anisodwr_bench_mumps
OUT=${1:-$ROOT/results/bench_mumps}
mkdir -p "$OUT"
CSV=$OUT/mumps.csv
"$BIN" --header >"$CSV"
for size in ${SIZES:-1:1:8 1:1:9 2:1:8 1:2:8}; do
  IFS=: read -r p r refs <<<"$size"
  "$BIN" "$p" "$r" 1e-6 "$refs" umfpack >>"$CSV"
  for n in ${RANKS:-1 2}; do
    mpirun --allow-run-as-root --oversubscribe -np "$n" "$BIN" "$p" "$r" 1e-6 "$refs" >>"$CSV"
  done
done
/usr/bin/python3 - "$CSV" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("| p | r | N_slab | solver | ranks | build s | factorize s | solve s | peak MB per rank (max) | peak MB (sum) | UMFPACK / this, factorize | residual |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
ref = {}
for x in rows:
    key = (x["p"], x["r"], x["refinements"])
    if x["solver"] == "umfpack":
        ref[key] = float(x["factorize_s"])
for x in rows:
    key = (x["p"], x["r"], x["refinements"])
    ratio = ref[key] / float(x["factorize_s"]) if key in ref else float("nan")
    print(f'| {x["p"]} | {x["r"]} | {x["N_slab"]} | {x["solver"]} | {x["ranks"]} | {float(x["build_s"]):.2f} | {float(x["factorize_s"]):.2f} | {float(x["solve_s"]):.3f} | {float(x["peak_mb_max"]):.0f} | {float(x["peak_mb_sum"]):.0f} | {ratio:.2f} | {float(x["residual"]):.1e} |')
PY
