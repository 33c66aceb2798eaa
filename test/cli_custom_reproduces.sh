#!/usr/bin/env bash
# Custom configs that state the built-in scenes as expressions and a mesh file give the
# built-in scenes' DWR loops: config/custom_moving_hump.json (f written out, found to be
# two products a_k(t) g_k(x)) that of config/moving_hump.json, config/custom_hemker.json
# (config/hemker.msh with its manifolds) that of config/hemker.json: N_space, N_t, N_tot
# equal, J, the estimates and the errors within 1e-10 relative, on 5 loops.
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"

hump=$src/config/moving_hump.json
custom=$src/config/custom_moving_hump.json
quiet=(--set output.vtu_every=0 --set output.vtu_loops=0 --set output.progress=false)

# 1. the moving hump: the same J_h, estimates, J errors and N on 5 DWR loops (round-off:
# 1e-10 relative)
expect 0 "results:" -- run "$hump" --output "$tmp/hump" --set adaptivity.loops=5 "${quiet[@]}"
expect 0 "results:" -- run "$custom" --output "$tmp/custom" --set adaptivity.loops=5 "${quiet[@]}"
same_loops "$tmp/hump/loops.csv" "$tmp/custom/loops.csv" 1e-10 || fail=1
# summary.json (12 digits): every number of the loops and goals (J_h, J_exact, weights,
# errors, estimates, probes) within 1e-10 relative plus 1e-13 absolute (the temporal
# estimates are differences of two primal solutions, ~1e-7: they differ by ~1e-15)
same_summary() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
skip = ("t_", "mem", "memory", "wall", "lu_", "concurrent")
bad = []
def walk(x, y, path):
    if isinstance(x, dict):
        if set(x) != set(y):
            bad.append(f"{path}: keys differ")
        for k in x:
            if k in y and not k.startswith(skip):
                walk(x[k], y[k], f"{path}.{k}")
    elif isinstance(x, list):
        if len(x) != len(y):
            bad.append(f"{path}: {len(x)} against {len(y)} entries")
        for i, (u, v) in enumerate(zip(x, y)):
            walk(u, v, f"{path}[{i}]")
    elif isinstance(x, (int, float)) and not isinstance(x, bool):
        if abs(x - y) > 1e-10 * abs(x) + 1e-13:
            bad.append(f"{path}: {x} vs {y}")
for key in sys.argv[3:] or ("loops", "levels", "goals"):
    if key in a:
        walk(a[key], b[key], key)
print("\n".join(bad[:10]) if bad else "summary.json: the same numbers")
sys.exit(1 if bad else 0)
PY
}
same_summary "$tmp/hump/summary.json" "$tmp/custom/summary.json" || fail=1
# ... and the same error norms (err_L2_T, err_nodal, err_L2L2) in a convergence study
# (Q1, dG(1), 2 levels)
study=(--set study.mode=convergence --set study.levels=2 --set discretization.p=1
  --set discretization.r=1 --set discretization.n_slabs=4 "${quiet[@]}")
expect 0 "results:" -- run "$hump" --output "$tmp/hump_c" "${study[@]}"
expect 0 "results:" -- run "$custom" --output "$tmp/custom_c" "${study[@]}"
same_summary "$tmp/hump_c/summary.json" "$tmp/custom_c/summary.json" levels || fail=1

# 2. Hemker: the mesh file with a polar and a transfinite manifold (5 loops; the goal
# columns against goal.reference included)
expect 0 "results:" -- run "$src/config/hemker.json" --output "$tmp/hemker" \
  --set adaptivity.loops=5 "${quiet[@]}"
expect 0 "results:" -- run "$src/config/custom_hemker.json" --output "$tmp/custom_hemker" \
  --set adaptivity.loops=5 "${quiet[@]}"
same_loops "$tmp/hemker/loops.csv" "$tmp/custom_hemker/loops.csv" 1e-10 || fail=1
exit $fail
