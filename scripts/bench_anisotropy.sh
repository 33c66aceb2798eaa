#!/usr/bin/env bash
# Anisotropic versus isotropic (and uniform) refinement on the boundary_layer scene:
# runs config/boundary_layer.json in each mode (same loop budget), then prints and
# writes (OUTDIR/anisotropy.csv) the spatial DoFs each mode needs to reach a set of
# J-error levels (log-log interpolation between loops) and the ratio iso/aniso.
# Usage: scripts/bench_anisotropy.sh [OUTDIR] [extra --set arguments...]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
OUT=${1:-$ROOT/results/bench_anisotropy}
shift || true
mkdir -p "$OUT"
for mode in anisotropic isotropic uniform; do
  loops=14
  [ "$mode" = uniform ] && loops=7
  "$BUILD/app/anisodwr" run "$ROOT/config/boundary_layer.json" --output "$OUT/$mode" \
    --set adaptivity.mode=$mode --set adaptivity.loops=$loops --set adaptivity.max_dofs=2e6 "$@" \
    | tail -n +2
done
/usr/bin/python3 "$ROOT/postprocess/compare_loops.py" "$OUT" anisotropic isotropic uniform
