#!/usr/bin/env bash
# Where methods fail: on hemker and moving_hump, one factor at a time from the reference
# settings (config/hemker_count.json, config/moving_hump_paper.json):
#   (a) Galerkin (delta0 = 0) versus SUPG delta0 = 0.1 and 1, adaptive and on uniform
#       meshes (equal DoFs by construction);
#   (b) isotropic versus anisotropic adaptivity;
#   (c) dG(0) versus dG(1) versus dG(2).
# Each run stops at STUDY_MAX_DOFS space-time DoFs (default 1.5e6) or STUDY_LOOPS loops.
# Then postprocess/stability_table.py prints a Markdown table and writes
# OUTDIR/stability.csv, and postprocess/charts.py draws the charts into OUTDIR/charts.
# Usage: scripts/stability_study.sh [OUTDIR]   (default results/stability)
# Env: STUDY_SCENES="hemker moving_hump" (subset), STUDY_LOOPS, STUDY_MAX_DOFS.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
OUT=${1:-$ROOT/results/stability}
mkdir -p "$OUT"
LOOPS=${STUDY_LOOPS:-9}
MAX_DOFS=${STUDY_MAX_DOFS:-1.5e6}

run() { # scene name config --set ...
  local scene=$1 name=$2 config=$3
  shift 3
  local dir="$OUT/${scene}_$name"
  local start=$SECONDS
  if ! "$BUILD/app/anisodwr" run "$ROOT/config/$config" --output "$dir" \
    --set adaptivity.loops="$LOOPS" --set adaptivity.max_dofs="$MAX_DOFS" \
    --set output.vtu_loops=1 "$@" >"$dir.log" 2>&1; then
    echo "run $scene/$name FAILED (exit code $?): see $dir.log" >&2
  fi
  echo "$scene/$name: $((SECONDS - start)) s" >&2
}

for scene in ${STUDY_SCENES:-hemker moving_hump}; do
  if [ "$scene" = hemker ]; then
    config=hemker_count.json base=0.1 other=1
  else
    config=moving_hump_paper.json base=1 other=0.1
  fi
  run "$scene" reference "$config"
  run "$scene" galerkin "$config" --set discretization.delta0=0
  run "$scene" "supg_$other" "$config" --set discretization.delta0=$other
  run "$scene" isotropic "$config" --set adaptivity.mode=isotropic
  run "$scene" dG1 "$config" --set discretization.r=1
  run "$scene" dG2 "$config" --set discretization.r=2
  for d in 0 0.1 1; do
    run "$scene" "uniform_delta$d" "$config" --set adaptivity.mode=uniform \
      --set discretization.delta0=$d --set adaptivity.loops=6 --set adaptivity.theta_tau=0
  done
done
/usr/bin/python3 "$ROOT/postprocess/stability_table.py" "$OUT"
