#!/usr/bin/env bash
# Slab solvers on the matrices a DWR run solves: for each scene and loop, run the DWR
# loops with output.dump_slab_loop (the first primal and adjoint slab matrix of that
# loop), then solve each matrix (the adjoint's transposed) with every solver in its own
# process (bench/bench_mtx.cc): UMFPACK and MUMPS (PETSc, factorization reused over the
# right-hand sides), GMRES(30) with ILU(1)/ILU(2) on the whole slab matrix, PETSc's
# BoomerAMG with its defaults, and hypre's BoomerAMG with approximate ideal restriction
# (AIR-1, AIR-2: one-point interpolation, F-F-C Jacobi post-relaxation). Tolerance 1e-10
# on the relative residual, at most 500 iterations, 3 right-hand sides per matrix.
# Writes OUT/bench_mtx.csv and prints a Markdown table.
# Usage: scripts/bench_mtx.sh [OUT]
# Env: CASES = "config:loop ..." (default: hemker_count loops 10 12 14, moving hump 10 12),
#      SOLVERS (default "umfpack mumps ilu1 ilu2 boomeramg air1 air2"; also umfpack_own:
#      anisodwr's own UMFPACK wrapper, with UMFPACK's predicted and actual peak and the
#      factors' size in the CSV's umf_* columns).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=${ANISODWR_BUILD_DIR:-$ROOT/build}
OUT=${1:-$ROOT/results/bench_mtx}
CASES=${CASES:-"hemker_count:10 hemker_count:12 hemker_count:14 moving_hump:10 moving_hump:12"}
SOLVERS=${SOLVERS:-"umfpack mumps ilu1 ilu2 boomeramg air1 air2"}
mkdir -p "$OUT"
CSV=$OUT/bench_mtx.csv
echo "scene,loop,problem,N_space,ar_max,$("$BUILD/bench/anisodwr_bench_mtx" --header)" >"$CSV"

solver_args() {
  case $1 in
  umfpack | mumps) echo "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type $1" ;;
  ilu1 | ilu2) echo "-ksp_type gmres -ksp_pc_side right -ksp_gmres_restart 30 -pc_type ilu -pc_factor_levels ${1#ilu}" ;;
  boomeramg) echo "-ksp_type gmres -ksp_pc_side right -ksp_gmres_restart 30 -pc_type hypre -pc_hypre_type boomeramg" ;;
  air1 | air2) echo "--air ${1#air}" ;;
  umfpack_own) echo "--own-umfpack" ;;
  *) echo "bench_mtx.sh: unknown solver '$1'" >&2 && exit 2 ;;
  esac
}

for c in $CASES; do
  IFS=: read -r scene loop <<<"$c"
  dir=$OUT/$scene-$loop
  "$BUILD/app/anisodwr" run "$ROOT/config/$scene.json" --output "$dir" \
    --set adaptivity.loops="$loop" --set output.dump_slab_loop="$loop" \
    --set output.vtu_loops=0 --set output.progress=false >"$dir.log"
  # N_space and the largest aspect ratio of the dumped loop
  read -r nspace ar < <(/usr/bin/python3 - "$dir/loops.csv" "$loop" <<'PY'
import csv, sys
for r in csv.DictReader(open(sys.argv[1])):
    if r["loop"] == sys.argv[2]:
        print(r["N_space"], r["ar_max"])
PY
)
  for problem in primal adjoint; do
    mtx=$dir/slab-$problem-loop-$(printf %04d "$loop").mtx
    flag=""
    [ "$problem" = adjoint ] && flag=--transpose
    for s in $SOLVERS; do
      # shellcheck disable=SC2046
      line=$("$BUILD/bench/anisodwr_bench_mtx" "$mtx" "$s" $flag $(solver_args "$s") 2>/dev/null |
        grep "^$s," || echo "$s,,,,,,0,,,,,,")
      echo "$scene,$loop,$problem,$nspace,$ar,$line" | tee -a "$CSV"
    done
    rm -f "$mtx"
  done
done

/usr/bin/python3 - "$CSV" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("| scene, loop | problem | N_space | AR | unknowns | solver | setup s | solve s | iterations | converged | s/slab amortized | peak MB |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    if not r["setup_s"]:
        print(f'| {r["scene"]} {r["loop"]} | {r["problem"]} | {r["N_space"]} | | | {r["label"]} | failed | | | **no** | | |')
        continue
    am = float(r["setup_s"]) / 10 + float(r["solve_s"])
    conv = "yes" if r["converged"] == "1" else "**no** (%.2g)" % float(r["residual"])
    print(f'| {r["scene"]} {r["loop"]} | {r["problem"]} | {r["N_space"]} | {float(r["ar_max"]):.0f} | {r["unknowns"]} | {r["label"]} | {float(r["setup_s"]):.3g} | {float(r["solve_s"]):.3g} | {float(r["iterations"]):.0f} | {conv} | {am:.3g} | {float(r["peak_mb"]):.0f} |')
PY
