#!/usr/bin/env bash
# Slab solver benchmark: UMFPACK (factorization reused) vs Belos/Ifpack2/Kronecker on the
# moving hump slab systems, each configuration in its own process (peak memory), all
# appended to one CSV; then postprocess/solver_table.py prints the tables, writes
# solver_table.md and solver_chart.png.
#
# Usage: scripts/bench_solvers.sh [OUTDIR]     (default results/bench_solvers)
# Env:   BENCH_PARTS="sizes grid" (default both), BENCH_SLABS (default 3),
#        (about 30 minutes on 2 shared cores, largest run ~ 10 GB)
#        BENCH_MAX_REF_Q1 (largest refinement of the Q1 size sweep, default 10),
#        BENCH_MEM_GB (virtual memory cap per run, default 16; a run over it is "crashed")
#
# sizes: r = 1, eps = 1e-6, N_space from ~1e3 up: primal Q1 / adjoint Q2 / primal Q2 /
#        adjoint Q4 with direct and the best iterative combinations.
# grid:  N_space = 16641 for each system, r = 0..3, eps = 1e-2..1e-8, every combination
#        (Q2/Q4 systems: a subset).
set -uo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${ANISODWR_BUILD_DIR:-$ROOT/build}
BIN=$BUILD/bench/anisodwr_bench_solvers
OUT=${1:-$ROOT/results/bench_solvers}
PARTS=${BENCH_PARTS:-"sizes grid"}
SLABS=${BENCH_SLABS:-3}
MAXQ1=${BENCH_MAX_REF_Q1:-10}
MEM_KB=$((${BENCH_MEM_GB:-16} * 1024 * 1024))
mkdir -p "$OUT"
CSV=$OUT/solvers.csv
[ -f "$CSV" ] || "$BIN" --header >"$CSV"

run() { # system p r eps refs solver; skipped if already in the CSV (resumable)
  local line krylov=- prec=-
  [ "$6" = direct ] || { krylov=${6%%+*}; prec=${6#*+}; }
  if grep -q "^$1,$2,$3,$4,$5,[0-9]*,[0-9]*,$krylov,$prec," "$CSV"; then return; fi
  # A virtual memory cap keeps a too large UMFPACK run from taking the machine.
  line=$(ulimit -v "$MEM_KB" && "$BIN" "$1" "$2" "$3" "$4" "$5" "$6" "$SLABS" 2>"$OUT/last_stderr.txt")
  [ -n "$line" ] || line="$1,$2,$3,$4,$5,,,${6%%+*},${6#*+},crashed,,,,,,,$(cut -d' ' -f1 /proc/loadavg),\"$(tr '\n,"' ';;;' <"$OUT/last_stderr.txt" | head -c 300)\""
  echo "$line" >>"$CSV"
  echo "$line" | cut -d, -f1-16
}

BEST="direct gmres+kronecker gmres+kronecker_presb bicgstab+kronecker gmres+riluk"
ALL="direct gmres+ilut gmres+riluk gmres+block_jacobi gmres+block_gauss_seidel gmres+block_ilu
     gmres+kronecker gmres+kronecker_presb fgmres+kronecker bicgstab+kronecker bicgstab+riluk"

for part in $PARTS; do
  if [ "$part" = sizes ]; then
    # (system, p, refinements): N_space = (2^refs p + 1)^2
    for spec in $(seq -f "primal:1:%g" 5 "$MAXQ1") adjoint:2:4 adjoint:2:5 adjoint:2:6 \
      adjoint:2:7 adjoint:2:8 primal:2:4 primal:2:6 primal:2:8 adjoint:4:3 \
      adjoint:4:5 adjoint:4:6; do
      IFS=: read -r sys p refs <<<"$spec"
      solvers=$BEST
      [ "$sys:$p:$refs" != primal:1:10 ] || solvers="direct gmres+kronecker_presb gmres+kronecker"
      for s in $solvers; do run "$sys" "$p" 1 1e-6 "$refs" "$s"; done
    done
    # r = 0..3 on a finer mesh than the grid's
    for r in 0 2 3; do
      for s in $BEST; do run primal 1 "$r" 1e-6 8 "$s"; done
    done
  fi
  if [ "$part" = grid ]; then
    for spec in primal:1:7 adjoint:2:6 primal:2:6 adjoint:4:5; do
      IFS=: read -r sys p refs <<<"$spec"
      solvers=$ALL
      [ "$sys:$p" = primal:1 ] || [ "$sys:$p" = adjoint:2 ] || solvers=$BEST
      for eps in 1e-2 1e-4 1e-6 1e-8; do
        for r in 0 1 2 3; do
          for s in $solvers; do run "$sys" "$p" "$r" "$eps" "$refs" "$s"; done
        done
      done
    done
  fi
done
echo "uptime at end: $(uptime)" >>"$OUT/load.txt"
/usr/bin/python3 "$ROOT/postprocess/solver_table.py" "$CSV"
