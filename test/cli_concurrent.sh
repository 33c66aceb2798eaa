#!/usr/bin/env bash
# adaptivity.concurrent_marches: the adjoint marched in a second thread while the primal
# marches gives the same loops.csv as one march after the other (moving_hump_paper with
# fixed weights, moving_hump with goal.weights = estimate and the dG(r+1) primal), and
# the concurrent column says which loops ran concurrently: all of them with the key true
# (on a machine with more than one core), none with false. With goal.weights = auto
# (hemker: the adjoint's goal weights come from the primal) only the adjoint's operator
# is factorized beside the primal and its march waits for the weights: the same loops
# again; hemker's auto weights follow the lift differences recorded in summary.json.
# Coefficients that depend on time: the Krylov solves with frozen modes run
# concurrently too.
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"

column_values() { # loops.csv COLUMN: the column's distinct values
  /usr/bin/python3 - "$1" "$2" <<'PY'
import csv, sys
print(" ".join(sorted({r[sys.argv[2]] for r in csv.DictReader(open(sys.argv[1]))})))
PY
}

cores=$(nproc)
want_on=1
[ "$cores" -gt 1 ] || want_on=0

# both_ways NAME TOL CONFIG ARGS...: runs config/CONFIG.json with ARGS and
# concurrent_marches true and false (outputs $tmp/NAME_true, $tmp/NAME_false), compares
# their loops.csv within TOL and checks the concurrent column: want_on on every loop
# with true, 0 with false. Returns 1 on a failure.
both_ways() {
  local name=$1 tol=$2 config=$3 c msg on off rc=0
  shift 3
  for c in true false; do
    "$bin" run "$src/config/$config.json" "$@" --set output.vtu_loops=0 \
      --set adaptivity.concurrent_marches=$c --output "$tmp/${name}_$c" >/dev/null 2>&1 ||
      { echo "FAIL: $name concurrent_marches=$c"; return 1; }
  done
  msg=$(same_loops "$tmp/${name}_true/loops.csv" "$tmp/${name}_false/loops.csv" "$tol") || rc=1
  echo "$name, concurrent against sequential marches: $msg"
  on=$(column_values "$tmp/${name}_true/loops.csv" concurrent)
  off=$(column_values "$tmp/${name}_false/loops.csv" concurrent)
  if [ "$on" != "$want_on" ] || [ "$off" != 0 ]; then
    echo "FAIL: $name: concurrent column '$on' with true (want $want_on on $cores cores), '$off' with false (want 0)"
    rc=1
  fi
  return $rc
}

both_ways moving_hump_paper 1e-12 moving_hump_paper --set adaptivity.loops=7 || fail=1
both_ways moving_hump 1e-12 moving_hump --set adaptivity.loops=5 || fail=1

# Coefficients that depend on time (manufactured rotating): auto solves every slab by
# GMRES preconditioned by a frozen operator's modes, which runs without Trilinos, so the
# marches run concurrently as well. The same loops up to round-off: the concurrent
# marches' UMFPACK runs OpenBLAS on one thread, which changes the factors' last bits
# (J_error, about 1e-7 here, then moves by 1e-15 absolute).
both_ways rotating 1e-6 manufactured --set study.mode=dwr --set scene.variant=rotating \
  --set discretization.r=2 --set discretization.initial_refinements=2 \
  --set adaptivity.loops=4 || fail=1
/usr/bin/python3 - "$tmp/rotating_true/summary.json" <<'PY' || fail=1
import json, sys
k = json.load(open(sys.argv[1]))["krylov"]
if not (k["solves"] > 0 and k["frozen_factorizations"] > 0):
    sys.exit(f"FAIL: manufactured rotating should solve by Krylov with frozen modes: {k}")
print(f"manufactured rotating: {k['solves']} Krylov solves, {k['iterations']} iterations")
PY

# (tolerance_measure = parts and the DWR goal estimate: one adjoint for the weighted
# goal; hemker.json's own measure, goals, and its enriched estimate solve one adjoint per
# goal)
one_adjoint=(--set adaptivity.tolerance_measure=parts --set adaptivity.goal_estimate=dwr)
both_ways hemker_auto 1e-12 hemker --set adaptivity.loops=4 \
  "${one_adjoint[@]}" || fail=1
"$bin" run "$src/config/hemker.json" --set adaptivity.loops=2 --set output.vtu_loops=0 \
  "${one_adjoint[@]}" --output "$tmp/hemker" >/dev/null 2>&1 || { echo "FAIL: hemker"; fail=1; }
# summary.json records each goal's lift difference d; the weight is sign(d)/|J_h|, and
# +1/|J_h| where |d| <= 1e-8 |J_h| (hemker loop 1: the lift does not see u_xe2_I)
/usr/bin/python3 - "$tmp/hemker/summary.json" <<'PY' || fail=1
import json, sys
seen = {"unseen": 0, "negative": 0}
for loop in json.load(open(sys.argv[1]))["loops"]:
    for name, g in loop["goals"].items():
        d, J, w = g["lift_difference"], g["J_h"], g["weight"]
        unseen = abs(d) <= 1e-8 * abs(J)
        want = (1 if unseen or d >= 0 else -1) / abs(J)
        if abs(w - want) > 1e-10 * abs(want):  # summary.json keeps 12 digits
            sys.exit(f"FAIL: hemker loop {loop['loop']} {name}: weight {w}, want {want} (d = {d})")
        seen["unseen" if unseen else "negative" if d < 0 else "positive"] = 1
if not (seen["unseen"] and seen["negative"]):
    sys.exit(f"FAIL: hemker loops 1-2 should have an unseen and a negative lift difference: {seen}")
print("hemker, auto weights from the recorded lift differences: ok")
PY

# One adjoint per goal (per_goal_estimates): the adjoints do not depend on the auto
# weights and march concurrently, concurrent and sequential marches agree, and the
# combined indicators (the weighted sum of the goals' own) equal those of the one
# adjoint of the weighted goal up to round-off
both_ways hemker_goals 1e-12 hemker --set adaptivity.loops=2 "${one_adjoint[@]}" \
  --set adaptivity.per_goal_estimates=true || fail=1
/usr/bin/python3 - "$tmp/hemker/loops.csv" "$tmp/hemker_goals_true/loops.csv" <<'PY' || fail=1
import csv, sys
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert len(a) == len(b) == 2, (len(a), len(b))
for x, y in zip(a, b):
    for k in ("N_space", "J", "eta_hx", "eta_hy", "eta_tau", "eta_h_rho", "eta_h_supg"):
        u, v = float(x[k]), float(y[k])
        if abs(u - v) > 1e-9 * abs(u) + 1e-13:
            sys.exit(f"FAIL: hemker loop {x['loop']} {k}: one adjoint {u}, sum over goals {v}")
    if not y["eta_u_xe1_I"] or x["eta_u_xe1_I"]:
        sys.exit("FAIL: eta_<goal> should be filled with per_goal_estimates only")
print("hemker, the weighted sum of the goals' estimates against one adjoint: ok")
PY
exit $fail
