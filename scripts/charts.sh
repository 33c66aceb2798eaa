#!/usr/bin/env bash
# Regenerates the README's charts (doc/img/*.png) from the result tables of
#   scripts/stability_study.sh          -> results/stability/
#   anisodwr run config/hemker_count.json --set adaptivity.loops=60 --set adaptivity.max_wall_time=1800
#        --set adaptivity.max_memory_mb=23000 --set output.vtu_loops=2 --output results/hemker_30min_direct
#   the bulk-marking Hemker setting of doc/history.md ("DWR: Hemker with bulk marking"), 30 loops
#        -> results/hemker_bulk30
#   anisodwr run config/hemker.json   -> results/hemker/ (the shipped setting; VTU of loops 10, 20, 25)
#   anisodwr run config/convergence_{time_r0..r3,space_p1..p4}.json
#   anisodwr run config/custom_mesh.json --set adaptivity.loops=8 --set output.vtu_loops=8
# Charts whose inputs are missing are skipped with a message. Hemker meshes are drawn
# at loop 12 (2.7e5 cells; loop 14 has 1.2e6, slow to draw).
# Usage: scripts/charts.sh [RESULTS_DIR] [OUT_DIR]   (defaults results/, doc/img/)
set -uo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
R=${1:-$ROOT/results}
OUT=${2:-$ROOT/doc/img}
S=$R/stability
H=$R/hemker_30min_direct
B=$R/hemker_bulk30
mkdir -p "$OUT"
chart() { /usr/bin/python3 "$ROOT/postprocess/charts.py" "$@" && echo "wrote $2" || echo "skipped $2 (missing input)"; }
chart work-precision "$OUT/work_precision.png" "$S/moving_hump_reference=dG(0) aniso" \
  "$S/moving_hump_isotropic=dG(0) iso" "$S/moving_hump_dG1=dG(1) aniso" "$S/moving_hump_dG2=dG(2) aniso"
chart history "$OUT/moving_hump_history.png" "$S/moving_hump_reference"
chart history "$OUT/hemker_history.png" "$H"
chart goal-values "$OUT/hemker_goals.png" "$H=aniso 30 min" "$S/hemker_isotropic=iso"
chart mesh "$OUT/hemker_mesh.png" "$H" 12 aspect_ratio
chart mesh "$OUT/hemker_mesh_zoom.png" "$H" 12 u -1.6 0.2 -0.2 1.6
chart mesh "$OUT/hemker_mesh_zoom_ar.png" "$H" 12 aspect_ratio -1.2 0.4 0.5 1.2
chart mesh "$OUT/hemker_bulk_mesh.png" "$B" 30 aspect_ratio
chart mesh "$OUT/hemker_bulk_mesh_zoom_ar.png" "$B" 30 aspect_ratio -1.2 0.4 0.5 1.2
chart mesh "$OUT/hemker_shipped_mesh_zoom_ar.png" "$R/hemker" 20 aspect_ratio -1.2 0.4 0.5 1.2
chart cutlines "$OUT/hemker_cutlines.png" "$H" 2,6,-1
chart compare-cut "$OUT/hemker_galerkin_supg.png" normal -1 "$S/hemker_uniform_delta0=Galerkin" \
  "$S/hemker_uniform_delta0.1=SUPG 0.1" "$S/hemker_uniform_delta1=SUPG 1"
chart compare-cut "$OUT/hemker_x4_galerkin_supg.png" x4 -1 "$S/hemker_uniform_delta0=Galerkin" \
  "$S/hemker_uniform_delta0.1=SUPG 0.1" "$S/hemker_uniform_delta1=SUPG 1"
chart mesh "$OUT/moving_hump_mesh_iso.png" "$S/moving_hump_isotropic" -1 aspect_ratio
chart mesh "$OUT/moving_hump_mesh_aniso.png" "$S/moving_hump_reference" -1 aspect_ratio
chart mesh "$OUT/custom_mesh.png" "$R/custom_mesh" 8 u
conv=()
for c in time_r0 time_r1 time_r2 time_r3 space_p1 space_p2 space_p3 space_p4; do
  [ -f "$R/convergence_$c/convergence.csv" ] && conv+=("$R/convergence_$c/convergence.csv=$c")
done
[ ${#conv[@]} -gt 0 ] && chart convergence "$OUT/convergence.png" "${conv[@]}"
exit 0
