#!/usr/bin/env bash
# The same anisodwr binary on Debian's reference BLAS/LAPACK (selected through
# LD_LIBRARY_PATH) and on the installed OpenBLAS (libopenblas0-pthread, the system
# default once installed): hemker 17 loops and the moving hump 14 loops, phase times
# and whether loops.csv agrees (doc/results.md "BLAS under the direct solvers").
# Usage: scripts/bench_blas.sh [OUTDIR]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${ANISODWR_BUILD_DIR:-$ROOT/build}/app/anisodwr
OUT=${1:-$ROOT/results/bench_blas}
REF="/usr/lib/x86_64-linux-gnu/blas:/usr/lib/x86_64-linux-gnu/lapack"
[ -f /usr/lib/x86_64-linux-gnu/blas/libblas.so.3 ] || { echo "no reference BLAS" >&2; exit 1; }
mkdir -p "$OUT"
run() { # NAME CONFIG ARGS...
  local name=$1 cfg=$2
  shift 2
  rm -rf "$OUT/${name}_ref" "$OUT/${name}_open"
  LD_LIBRARY_PATH=$REF "$BIN" run "$ROOT/config/$cfg" --output "$OUT/${name}_ref" \
    --set output.vtu_loops=0 "$@" >"$OUT/${name}_ref.log"
  "$BIN" run "$ROOT/config/$cfg" --output "$OUT/${name}_open" --set output.vtu_loops=0 \
    "$@" >"$OUT/${name}_open.log"
}
run hemker hemker_count.json --set adaptivity.loops=17
run hump moving_hump_p1.json --set adaptivity.loops=14
/usr/bin/python3 - "$OUT" <<'PY'
import csv, sys
out = sys.argv[1]
for name in ["hemker", "hump"]:
    a = list(csv.DictReader(open(f"{out}/{name}_ref/loops.csv")))
    b = list(csv.DictReader(open(f"{out}/{name}_open/loops.csv")))
    print(f"\n{name}: {len(a)} loops")
    print("| phase | reference BLAS s | OpenBLAS s | ratio |\n|---|---|---|---|")
    ta = tb = 0.
    for ph in ["t_primal", "t_adjoint", "t_estimate", "t_refine"]:
        x = sum(float(r[ph]) for r in a); y = sum(float(r[ph]) for r in b)
        ta += x; tb += y
        print(f"| {ph} | {x:.1f} | {y:.1f} | {x / y:.2f} |")
    print(f"| total | {ta:.1f} | {tb:.1f} | {ta / tb:.2f} |")
    print(f"last loop adjoint: {float(a[-1]['t_adjoint']):.2f} s / {float(b[-1]['t_adjoint']):.2f} s")
    same = all(x["N_space"] == y["N_space"] and x["N_t"] == y["N_t"] for x, y in zip(a, b))
    worst = max(abs(float(x[k]) - float(y[k])) / abs(float(x[k]))
                for x, y in zip(a, b) for k in ["eta_hx", "eta_hy", "eta_tau", "J_error"]
                if x[k] and y[k] and float(x[k]) != 0)
    print(f"N_space, N_t identical: {same}; largest relative difference in eta, J error: {worst:.1e}")
PY
