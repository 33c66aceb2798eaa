#!/usr/bin/env bash
# Convergence orders in time and space (doc/results.md, "Convergence orders in time and
# space"): runs config/convergence_{time_r0..r3,space_p1..p4}.json and
# config/convergence_moving_hump.json into OUTDIR (default results/convergence_table) and
# prints the section's two tables (postprocess/convergence_table.py), also written to
# OUTDIR/convergence_table.md. Usage: scripts/convergence_table.sh [OUTDIR]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
OUT=${1:-$ROOT/results/convergence_table}
mkdir -p "$OUT"
for c in time_r0 time_r1 time_r2 time_r3 space_p1 space_p2 space_p3 space_p4 moving_hump; do
  echo "== convergence_$c"
  rm -rf "$OUT/convergence_$c"
  "$BUILD/app/anisodwr" run "$ROOT/config/convergence_$c.json" --output "$OUT/convergence_$c" \
    >"$OUT/convergence_$c.log" 2>&1
done
/usr/bin/python3 "$ROOT/postprocess/convergence_table.py" "$OUT" | tee "$OUT/convergence_table.md"
