#!/usr/bin/env bash
# Benchmark of the primal slab solver (UMFPACK) on the moving hump, uniform meshes,
# r = 0..3: assembly, factorization, solve per slab, total primal time, peak memory,
# and the speed-up of factorization reuse over refactorizing every slab.
# Each configuration runs in its own process (peak memory is per process): a single
# run (study.mode = single) with 5 slabs of config/moving_hump_p1.json's discretization.
# Usage: scripts/bench_slab.sh [OUTDIR]   (default results/bench_slab)
# Env: BENCH_SIZES="r:refs ..." overrides the (r, refinements) pairs.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
OUT=${1:-$ROOT/results/bench_slab}
mkdir -p "$OUT"
SIZES=${BENCH_SIZES:-"0:5 0:7 0:9 0:10 1:5 1:7 1:9 2:5 2:7 2:8 3:5 3:7 3:8"}
for pair in $SIZES; do
  r=${pair%%:*}
  refs=${pair##*:}
  for reuse in true false; do
    dir="$OUT/r${r}_ref${refs}_reuse_${reuse}"
    "$BUILD/app/anisodwr" run "$ROOT/config/moving_hump_p1.json" --output "$dir" \
      --set study.mode=single --set discretization.n_slabs=5 \
      --set discretization.r="$r" --set discretization.initial_refinements="$refs" \
      --set solver.reuse_factorization="$reuse" --set output.vtu_every=0 \
      --set output.progress=false >/dev/null
    echo "done r=$r refs=$refs reuse=$reuse" >&2
  done
done
/usr/bin/python3 "$ROOT/postprocess/bench_table.py" "$OUT"
