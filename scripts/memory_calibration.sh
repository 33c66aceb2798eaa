#!/usr/bin/env bash
# Memory estimate against the measured peak (VmHWM via getrusage): DWR loops of
# config/moving_hump_p1.json (UMFPACK and Krylov) and config/hemker_count.json, and single runs of
# the moving hump on uniform meshes. Each run in its own process, one after the other
# (run it alone: the peak of a process is what it measures). Prints a markdown table
# (run, loop or refinements, N_space, N_tot, measured MB, estimated MB, ratio) and
# writes it to OUTDIR/memory_calibration.md. About 8 minutes on 2 cores.
# Usage: scripts/memory_calibration.sh [OUTDIR]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
OUT=${1:-$ROOT/results/memory_calibration}
mkdir -p "$OUT"
bin=$BUILD/app/anisodwr
run() {
  local name=$1
  shift
  echo "== $name" >&2
  "$bin" run "$@" --output "$OUT/$name" >"$OUT/$name.log"
}
run moving_hump_direct "$ROOT/config/moving_hump_p1.json" --set goal.weights=1 --set discretization.r=1 --set adaptivity.space_indicator=average --set adaptivity.loops=16 --set output.vtu_loops=0
run moving_hump_krylov "$ROOT/config/moving_hump_p1.json" --set goal.weights=1 --set discretization.r=1 --set adaptivity.space_indicator=average --set adaptivity.loops=14 \
  --set solver.type=iterative --set output.vtu_loops=0
run hemker "$ROOT/config/hemker_count.json" --set adaptivity.loops=17 --set output.vtu_loops=0
for ref in 6 7 8; do
  run single_ref$ref "$ROOT/config/moving_hump_p1.json" --set study.mode=single \
    --set discretization.initial_refinements=$ref --set discretization.r=1 --set output.vtu_every=0
done
/usr/bin/python3 - "$OUT" <<'PY' | tee "$OUT/memory_calibration.md"
import csv, json, sys
out = sys.argv[1]
print("| run | loop / refinements | N_space | N_tot | measured MB | estimated MB | measured / estimated |")
print("|---|---|---|---|---|---|---|")
def row(name, at, n_space, n_tot, measured, estimate):
    print(f"| {name} | {at} | {int(float(n_space))} | {int(float(n_tot))} | {float(measured):.0f} "
          f"| {float(estimate):.0f} | {float(measured) / float(estimate):.2f} |")
for name in ("moving_hump_direct", "moving_hump_krylov", "hemker"):
    for r in csv.DictReader(open(f"{out}/{name}/loops.csv")):
        if int(r["loop"]) in (1, 4, 8) or int(r["loop"]) >= 10:
            row(name, r["loop"], r["N_space"], r["N_tot"], r["mem_peak"], r["memory_estimate_mb"])
for ref in (6, 7, 8):
    d = json.load(open(f"{out}/single_ref{ref}/summary.json"))
    l = d["levels"][0]
    row("moving_hump single", ref, l["N_space"], l["N_tot"], d["peak_memory_mb"], l["memory_estimate_mb"])
PY
