#!/usr/bin/env bash
# Serial against MPI on this machine: one DWR run per variant, back to back,
#   umfpack_1thread  1 process, DEAL_II_NUM_THREADS=1, UMFPACK
#   umfpack          1 process, all cores (the serial default)
#   mumps            1 process, all cores, solver.direct = mumps
#   mpiN             mpirun -np N (MUMPS; cores shared out between the ranks)
#   mpiN_umfpack     mpirun -np N with solver.direct = umfpack (every rank factorizes
#                    and solves the whole slab system itself; only the estimator is shared)
#   scripts/bench_mpi.sh CONFIG LOOPS [--set key=value ...]
# then postprocess/mpi_table.py OUT: whether all variants reproduce the serial loops
# (N_space, N_t, J), and for the last loop and the one four before it the phase times,
# the largest rank's peak memory and the speed-ups against the serial default and
# against one thread. Env: OUT (default results/bench_mpi; a directory
# per config below it), RANKS (default 2), CHART (a PNG path for the bar chart), REPEAT
# (default 1: rounds of all variants; the table keeps each variant's fastest round),
# FIRST (default 1; FIRST=2 REPEAT=2 adds a second round to an existing OUT).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${BIN:-$ROOT/build/app/anisodwr}
CONFIG=$1 LOOPS=$2
shift 2
BASE=${OUT:-results/bench_mpi}
OUT=$BASE/$(basename "$CONFIG" .json)
RANKS=${RANKS:-2}
mkdir -p "$OUT"
common=(run "$CONFIG" --set adaptivity.loops="$LOOPS" --set output.vtu_loops=0 "$@")
REPEAT=${REPEAT:-1}
mpi=(mpirun --allow-run-as-root --oversubscribe -np "$RANKS")
# the variants in turn, REPEAT rounds (round k > 1 writes VARIANT.k; the table takes
# the fastest round of each variant, per loop)
for ((k = ${FIRST:-1}; k <= REPEAT; ++k)); do
  sfx=$([ "$k" = 1 ] && echo "" || echo ".$k")
  DEAL_II_NUM_THREADS=1 "$BIN" "${common[@]}" --output "$OUT/umfpack_1thread$sfx" >/dev/null
  "$BIN" "${common[@]}" --output "$OUT/umfpack$sfx" >/dev/null
  "$BIN" "${common[@]}" --set solver.direct=mumps --output "$OUT/mumps$sfx" >/dev/null
  "${mpi[@]}" "$BIN" "${common[@]}" --output "$OUT/mpi$RANKS$sfx" >/dev/null
  "${mpi[@]}" "$BIN" "${common[@]}" --set solver.direct=umfpack \
    --output "$OUT/mpi${RANKS}_umfpack$sfx" >/dev/null
done
/usr/bin/python3 "$ROOT/postprocess/mpi_table.py" "$BASE" ${CHART:+"$CHART"}
