#!/usr/bin/env bash
# AMG (ML, solver.spatial_preconditioner = amg) versus ILU(k) inside the Kronecker
# preconditioners versus UMFPACK on moving hump slab systems, each configuration in its
# own process (peak memory) via anisodwr_bench_solvers, all in one CSV; tables by
# postprocess/solver_table.py (N sweep, iterations over eps x r) and
# postprocess/amg_table.py (aspect ratio sweep, summary).
#
# Usage: scripts/bench_amg.sh [OUTDIR]      (default results/bench_amg; resumable)
# Env:   BENCH_PARTS="grid sizes aniso" (default all), BENCH_SLABS (default 3),
#        BENCH_MEM_GB (virtual memory cap per run, default 16)
#
# grid:  primal Q1 (N_space 16641) and adjoint Q2 (N_space 16641), eps 1e-2..1e-8, r 0..3
# sizes: primal Q1, r = 1, eps = 1e-6, N_space 4225 .. 263169
# aniso: primal Q1, r = 1, eps = 1e-6, 33 x 33 vertices refined k times in y only
#        (aspect ratio 2^k, k = 0, 3, 6, 9)
set -uo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${ANISODWR_BUILD_DIR:-$ROOT/build}
BIN=$BUILD/bench/anisodwr_bench_solvers
OUT=${1:-$ROOT/results/bench_amg}
PARTS=${BENCH_PARTS:-"grid sizes aniso"}
SLABS=${BENCH_SLABS:-3}
MEM_KB=$((${BENCH_MEM_GB:-16} * 1024 * 1024))
mkdir -p "$OUT"
CSV=$OUT/amg.csv
[ -f "$CSV" ] || "$BIN" --header >"$CSV"

run() { # system p r eps refs solver [aniso]; skipped if already in the CSV (resumable)
  local line krylov=- prec=- aniso=${7:-0}
  [ "$6" = direct ] || { krylov=${6%%+*}; prec=${6#*+}; }
  if grep -q "^$1,$2,$3,$4,$5,[0-9]*,[0-9]*,$krylov,$prec,.*,$((1 << aniso))\$" "$CSV"; then return; fi
  line=$(ulimit -v "$MEM_KB" && BENCH_ANISO=$aniso "$BIN" "$1" "$2" "$3" "$4" "$5" "$6" "$SLABS" 2>"$OUT/last_stderr.txt")
  [ -n "$line" ] || line="$1,$2,$3,$4,$5,,,$krylov,$prec,crashed,,,,,,,$(cut -d' ' -f1 /proc/loadavg),\"$(tr '\n,"' ';;;' <"$OUT/last_stderr.txt" | head -c 300)\",$((1 << aniso))"
  echo "$line" >>"$CSV"
  echo "$line" | cut -d, -f1-16
}

SOLVERS="direct gmres+kronecker_presb gmres+kronecker_presb@amg gmres+kronecker_presb@amg-gs
         gmres+kronecker@amg"
for part in $PARTS; do
  case $part in
  grid)
    for spec in primal:1:7 adjoint:2:6; do
      IFS=: read -r sys p refs <<<"$spec"
      for eps in 1e-2 1e-4 1e-6 1e-8; do
        for r in 0 1 2 3; do
          for s in $SOLVERS; do run "$sys" "$p" "$r" "$eps" "$refs" "$s"; done
        done
      done
    done
    ;;
  sizes)
    for refs in 6 7 8 9; do
      for s in $SOLVERS; do run primal 1 1 1e-6 "$refs" "$s"; done
    done
    ;;
  aniso)
    for k in 0 3 6 9; do
      for s in $SOLVERS; do run primal 1 1 1e-6 5 "$s" "$k"; done
    done
    ;;
  esac
done
echo "uptime at end: $(uptime)" >>"$OUT/load.txt"
/usr/bin/python3 "$ROOT/postprocess/solver_table.py" "$CSV" >/dev/null
/usr/bin/python3 "$ROOT/postprocess/amg_table.py" "$CSV"
