#!/usr/bin/env bash
# Marking strategies on config/hemker.json (same loops, same theta_h = 1/3): joint
# (cell, direction) ranking, per_direction (the reference rule, doc/method.md §9), and
# cell marking with kappa = 0.5, 0.75, 1. Prints and writes OUTDIR/marking.csv (one row
# per variant and loop: N_space, growth, J_1, J_2, y_layer, y_layer * N_space, cells
# marked in x / y / both, closure) and OUTDIR/marking.md; charts y_layer and J_1 against
# N_space (OUTDIR/marking.png).
# Usage: scripts/bench_marking.sh [OUTDIR] [LOOPS]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
OUT=${1:-$ROOT/results/bench_marking}
LOOPS=${2:-10}
mkdir -p "$OUT"
run() {
  local name=$1
  shift
  echo "== $name"
  "$BUILD/app/anisodwr" run "$ROOT/config/hemker.json" --output "$OUT/$name" \
    --set adaptivity.loops=$LOOPS --set output.vtu_loops=0 "$@" | tail -n 2
}
run joint --set adaptivity.marking=joint
run per_direction --set adaptivity.marking=per_direction
for k in 0.5 0.75 1; do
  run cell_k$k --set adaptivity.marking=cell --set adaptivity.kappa=$k
done
/usr/bin/python3 "$ROOT/postprocess/marking_table.py" "$OUT" joint per_direction \
  cell_k0.5 cell_k0.75 cell_k1
