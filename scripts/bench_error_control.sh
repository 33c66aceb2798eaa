#!/usr/bin/env bash
# Error control without tuning: problems nobody tuned, each run with the default
# adaptivity keys and only a tolerance (adaptivity.tolerance, its measure and the stop
# as documented in doc/keys.md), until the tolerance stops it (or LOOPS loops).
# Prints and writes OUTDIR/error_control.csv (one row per problem and loop),
# OUTDIR/error_control.md (one row per problem: the loop of the stop, N_tot, the error
# at the stop against the tolerance, I_eff over the loops with N_tot >= 1e5, the balance
# of eta_h and eta_tau at the stop, wall time) and the chart OUTDIR/error_control.png.
# Usage: scripts/bench_error_control.sh [OUTDIR] [PROBLEM ...]   (default: all)
# Env: LOOPS (default 40), the loop limit beside the tolerance; MAX_WALL (default 300 s),
# adaptivity.max_wall_time of each run; EXTRA_SET (default empty), further key=value
# overrides given to every run (e.g. "adaptivity.time_balance=0.1"), for a comparison;
# TOL_SCALE (default 1), a factor on every problem's tolerance (0.1: each run refined
# past its benchmark stop).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
OUT=${1:-$ROOT/results/bench_error_control}
shift || true
LOOPS=${LOOPS:-40}
MAX_WALL=${MAX_WALL:-300}
TOL_SCALE=${TOL_SCALE:-1}
extra=()
for kv in ${EXTRA_SET:-}; do extra+=(--set "$kv"); done
mkdir -p "$OUT/configs"

# name | tolerance | config: a file in config/ or the scene/discretization/goal sections
# written here (no adaptivity keys: the defaults apply)
problems=(
  "moving_hump_p2r2|1e-3|{\"scene\": {\"name\": \"moving_hump\", \"epsilon\": 1e-6, \"end_time\": 0.5}, \"discretization\": {\"p\": 2, \"r\": 2, \"initial_refinements\": 2, \"n_slabs\": 10}, \"goal\": {\"kind\": \"scene\", \"radius\": 0.01}}"
  "moving_hump_p1r0|1e-2|{\"scene\": {\"name\": \"moving_hump\", \"epsilon\": 1e-6, \"end_time\": 0.5}, \"discretization\": {\"p\": 1, \"r\": 0, \"initial_refinements\": 2, \"n_slabs\": 5}, \"goal\": {\"kind\": \"scene\", \"radius\": 0.01}}"
  "boundary_layer|3e-3|{\"scene\": {\"name\": \"boundary_layer\", \"epsilon\": 1e-3, \"end_time\": 0.5}, \"discretization\": {\"p\": 1, \"r\": 1, \"supg_length\": \"streamline\", \"initial_refinements\": 2, \"n_slabs\": 5}, \"goal\": {\"kind\": \"scene\"}}"
  "manufactured_constant|1e-5|{\"scene\": {\"name\": \"manufactured\", \"variant\": \"constant\", \"epsilon\": 1e-2, \"end_time\": 0.5}, \"discretization\": {\"p\": 2, \"r\": 1, \"initial_refinements\": 2, \"n_slabs\": 5}, \"goal\": {\"kind\": \"scene\"}}"
  "manufactured_rotating|1e-5|{\"scene\": {\"name\": \"manufactured\", \"variant\": \"rotating\", \"epsilon\": 1e-2, \"end_time\": 0.5}, \"discretization\": {\"p\": 2, \"r\": 1, \"initial_refinements\": 2, \"n_slabs\": 5}, \"goal\": {\"kind\": \"scene\"}}"
  "heat_trig|1e-5|{\"scene\": {\"name\": \"heat\", \"variant\": \"trig\", \"epsilon\": 1, \"end_time\": 1}, \"discretization\": {\"p\": 2, \"r\": 1, \"delta0\": 0, \"initial_refinements\": 2, \"n_slabs\": 5}, \"goal\": {\"kind\": \"scene\"}}"
  "rotating_hill|2e-3|config/rotating_hill.json"
  "hartmann_hill|5e-4|config/hartmann_hill.json"
  "custom_neumann_rectangle|1e-4|config/custom_neumann.json"
)

selected=("$@")
names=()
for entry in "${problems[@]}"; do
  IFS='|' read -r name tol config <<<"$entry"
  if [ ${#selected[@]} -gt 0 ] && [[ ! " ${selected[*]} " =~ " $name " ]]; then
    continue
  fi
  names+=("$name")
  tol=$(/usr/bin/python3 -c "print('%g' % ($tol * $TOL_SCALE))")
  if [[ "$config" == config/* ]]; then
    file="$ROOT/$config"
  else
    file="$OUT/configs/$name.json"
    printf '%s\n' "${config%\}}, \"study\": {\"mode\": \"dwr\"}}" >"$file"
  fi
  echo "== $name (tolerance $tol)"
  start=$(date +%s.%N)
  status=0
  "$BUILD/app/anisodwr" run "$file" --output "$OUT/$name" --set adaptivity.tolerance="$tol" \
    --set adaptivity.loops="$LOOPS" --set adaptivity.max_wall_time="$MAX_WALL" --set output.vtu_loops=0 --set output.progress=false "${extra[@]}" \
    >"$OUT/$name.log" 2>&1 || status=$?
  end=$(date +%s.%N)
  tail -n 4 "$OUT/$name.log"
  echo "$tol $(/usr/bin/python3 -c "print($end - $start)") $status" >"$OUT/$name.run"
done
/usr/bin/python3 "$ROOT/postprocess/error_control.py" "$OUT" "${names[@]}"
