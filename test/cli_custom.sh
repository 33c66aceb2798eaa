#!/usr/bin/env bash
# The custom scene (scene.name = custom): a config that states the moving hump as
# expressions gives the built-in scene's DWR loops and errors; the shipped custom configs
# run; bad input gives exit code 2 and a message naming the key.
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"

hump=$src/config/moving_hump.json
custom=$src/config/custom_moving_hump.json
mesh=$src/config/custom_mesh.json
example=$src/config/custom_example.json
quiet=(--set output.vtu_every=0 --set output.vtu_loops=0 --set output.progress=false)

# 1. the same J_h, estimates, J errors and N on 2 DWR loops (round-off: 1e-10 relative)
expect 0 "results:" -- run "$hump" --output "$tmp/hump" --set adaptivity.loops=2 "${quiet[@]}"
expect 0 "results:" -- run "$custom" --output "$tmp/custom" --set adaptivity.loops=2 "${quiet[@]}"
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

# 2. the shipped configs run (2 loops)
expect 0 "results:" -- run "$example" --output "$(o)" --set adaptivity.loops=2 "${quiet[@]}"
expect 0 "results:" -- run "$mesh" --output "$(o)" --set adaptivity.loops=2 "${quiet[@]}"

# 3. bad input: exit 2, naming the key
expect 2 "boundary id 3 of the domain .*has no condition" -- run "$mesh" --output "$(o)" \
  --set "scene.neumann=2: 0"
expect 2 "boundary id 7 in key 'scene.dirichlet' is not a boundary id" -- run "$mesh" \
  --output "$(o)" --set "scene.dirichlet=1: 0; 4, 7: 1"
expect 2 "invalid expression 'sin(x' for key 'scene.rhs'" -- run "$mesh" --output "$(o)" \
  --set "scene.rhs=sin(x"
expect 2 "for key 'scene.reaction'.*\"z\"" -- run "$mesh" --output "$(o)" --set "scene.reaction=z"
expect 2 "for key 'scene.convection'; expected two expressions" -- run "$mesh" --output "$(o)" \
  --set "scene.convection=1"
expect 2 "scene.constants" -- run "$mesh" --output "$(o)" --set "scene.constants=1a = 2"
expect 2 "scene.mesh_file.*cannot read" -- run "$mesh" --output "$(o)" \
  --set scene.mesh_file=nonexistent.msh
expect 2 "scene.mesh_file.*is not a Gmsh mesh" -- run "$mesh" --output "$(o)" \
  --set "scene.mesh_file=$src/config/custom_mesh.json"
expect 2 "scene.grid" -- run "$example" --output "$(o)" --set scene.grid=hyper_cubus
expect 2 "scene.goals.*outside the domain" -- run "$mesh" --output "$(o)" \
  --set "scene.goals=point 1, 0.5"
expect 2 "key 'scene.rhs' does not match scene.exact_solution" -- run "$example" --output "$(o)" \
  --set "scene.rhs=0"
expect 2 "scene.variant" -- run "$mesh" --output "$(o)" --set scene.variant=rotating
# 4. flux goals: Hemker's heat flux from the circle beside the point goals, with its
# own estimate; bad flux locations
hflux=$src/config/hemker_flux.json
expect 0 "results:" -- run "$hflux" --output "$tmp/hflux" --set adaptivity.loops=2 "${quiet[@]}"
/usr/bin/python3 - "$tmp/hflux" <<'PY' || fail=1
import csv, json, math, sys
s = json.load(open(sys.argv[1] + "/summary.json"))
rows = list(csv.DictReader(open(sys.argv[1] + "/loops.csv")))
J = [l["goals"]["heat_I"]["J_h"] for l in s["loops"]]
eta = [float(r["eta_heat_I"]) for r in rows]
ok = len(J) == 2 and all(math.isfinite(x) and x > 0 for x in J + eta)
print("heat_I: J_h", J, "eta", eta, "ok" if ok else "FAILED")
sys.exit(0 if ok else 1)
PY
flux=(--set goal.reference= --set goal.over_time=true)
expect 2 "boundary id 2 is a Neumann boundary" -- run "$hflux" --output "$(o)" "${flux[@]}" \
  --set "goal.locations=heat = flux 2"
expect 2 "boundary id 9 is not a boundary of the domain" -- run "$hflux" --output "$(o)" \
  "${flux[@]}" --set "goal.locations=flux 1, 9"
expect 2 "a flux goal is integrated over I" -- run "$hflux" --output "$(o)" \
  --set goal.reference= --set goal.over_time=false --set "goal.locations=flux 1"
expect 2 "invalid value 'a' in key 'goal.locations'; expected one or more" -- run "$hflux" \
  --output "$(o)" "${flux[@]}" --set "goal.locations=flux a"
exit $fail
