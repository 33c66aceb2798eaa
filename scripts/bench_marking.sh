#!/usr/bin/env bash
# Marking strategies on config/hemker_count.json (same loops, same theta_h = 1/3 of the
# cells): joint (cell, direction) ranking, per_direction (the reference rule,
# doc/method.md §9), and cell marking with kappa = 0.5, 0.75, 1; then cell marking
# (kappa = 0.75) by the bulk criterion with theta_h = 0.5, 0.7 (config/hemker.json), 0.8,
# 0.9 of the summed indicators, which adds fewer cells per loop and therefore runs up to
# BULK_LOOPS loops, until N_space would exceed BULK_N_SPACE. Prints and writes
# OUTDIR/marking.csv (one row per variant and loop: N_space, growth, J_1, J_2, y_layer,
# y_layer * N_space, cells marked in x / y / both, closure) and OUTDIR/marking.md; charts
# y_layer and J_1 against N_space (OUTDIR/marking.png).
# Usage: scripts/bench_marking.sh [OUTDIR] [LOOPS]
# Env: BULK_LOOPS (default 60), BULK_N_SPACE (default 1e5).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
OUT=${1:-$ROOT/results/bench_marking}
LOOPS=${2:-10}
mkdir -p "$OUT"
run() {
  local name=$1
  shift
  echo "== $name"
  "$BUILD/app/anisodwr" run "$ROOT/config/hemker_count.json" --output "$OUT/$name" \
    --set adaptivity.loops=$LOOPS --set output.vtu_loops=0 "$@" | tail -n 2
}
run joint --set adaptivity.marking=joint
run per_direction --set adaptivity.marking=per_direction
for k in 0.5 0.75 1; do
  run cell_k$k --set adaptivity.marking=cell --set adaptivity.kappa=$k
done
# 36 slabs of dG(0): N_tot = 36 N_space
max_dofs=$(/usr/bin/python3 -c "print(36 * float('${BULK_N_SPACE:-1e5}'))")
for t in 0.5 0.7 0.8 0.9; do
  LOOPS=${BULK_LOOPS:-60} run bulk_$t --set adaptivity.marking_criterion=bulk \
    --set adaptivity.theta_h=$t --set adaptivity.max_dofs="$max_dofs"
done
/usr/bin/python3 "$ROOT/postprocess/marking_table.py" "$OUT" joint per_direction \
  cell_k0.5 cell_k0.75 cell_k1 bulk_0.5 bulk_0.7 bulk_0.8 bulk_0.9
