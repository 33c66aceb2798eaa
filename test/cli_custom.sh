#!/usr/bin/env bash
# The custom scene (scene.name = custom): the shipped custom configs run; bad input gives
# exit code 2 and a message naming the key. (That custom configs reproduce the built-in
# scenes: cli_custom_reproduces.sh.)
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"

mesh=$src/config/custom_mesh.json
example=$src/config/custom_example.json
quiet=(--set output.vtu_every=0 --set output.vtu_loops=0 --set output.progress=false)

# 1. the shipped configs run (2 loops)
expect 0 "results:" -- run "$example" --output "$(o)" --set adaptivity.loops=2 "${quiet[@]}"
expect 0 "results:" -- run "$mesh" --output "$(o)" --set adaptivity.loops=2 "${quiet[@]}"

# 2. bad input: exit 2, naming the key
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
# 3. flux goals: Hemker's heat flux from the circle beside the point goals, with its
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
# the flux goal's effectivity on a smooth manufactured case (Q1, dG(1), the primal-residual
# form of eta_h, the default; the primal is Galerkin, so is the adjoint): I_eff in
# [0.9, 1.1] on every loop with N_tot >= 1e5 (measured 1.00 on loops 7-12 with the conforming
# weights at hanging nodes, the default; 0.78-0.87 with the cell-wise ones; the default
# time_balance bisects no slab, eta_tau being 1e-4 of eta_h)
expect 0 "results:" -- run "$src/config/manufactured.json" --output "$tmp/fman" "${quiet[@]}" \
  --set scene.variant=constant --set study.mode=dwr --set goal.kind=flux \
  --set "goal.locations=flux 0" --set goal.over_time=true --set discretization.p=1 \
  --set adaptivity.loops=12
/usr/bin/python3 - "$tmp/fman/loops.csv" <<'PY' || fail=1
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if int(r["N_tot"]) >= 1e5]
ieff = [float(r["I_eff"]) for r in rows]
ok = len(ieff) >= 2 and all(0.9 <= x <= 1.1 for x in ieff)
print("flux I_eff on N_tot >= 1e5:", ieff, "ok" if ok else "FAILED")
sys.exit(0 if ok else 1)
PY
# The Dirichlet data's share of eta_h (loops.csv eta_h_data) on config/hartmann_hill.json,
# whose boundary data u = 1/(1 + 50 |x - m(t)|^2) vary along the walls: it is non-zero on
# every loop and falls as the walls are refined (at loop 11 below a tenth of its largest
# value; measured 1.5e-2 at loop 3, 1.4e-4 at loop 11), and the mean goal's error with it
# (measured 2.8e-6 and 4.3e-6 at loops 10-11; where the estimator missed the term, the
# boundary cells stayed coarse and that error stalled at 1.2e-3).
expect 0 "results:" -- run "$src/config/hartmann_hill.json" --output "$tmp/hill" "${quiet[@]}" \
  --set adaptivity.tolerance=0 --set adaptivity.loops=11 --set adaptivity.per_goal_estimates=true
/usr/bin/python3 - "$tmp/hill/loops.csv" <<'PY' || fail=1
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
data = [float(r["eta_h_data"]) for r in rows]
err = [abs(float(r["err_mean_all"])) for r in rows]
ok = (len(rows) == 11 and all(d != 0 for d in data) and abs(data[-1]) < max(abs(d) for d in data) / 10
      and max(err[-2:]) < 3e-4)
print("hartmann eta_h_data", data[0], "->", data[-1], "mean error", err[-2:],
      "ok" if ok else "FAILED")
sys.exit(0 if ok else 1)
PY
# 5. u = x y with b = 0, alpha = 0, f = 0: the data check accepts the exact solution
# (its PDE residual is pure round-off), and the flux goal on x = 1 next to Neumann data
# given per boundary id is exact to round-off: int_I int_{x=1} eps d_x u = eps T / 2 = 0.5
cat >"$tmp/xy.json" <<'JSON'
{"scene": {"name": "custom", "epsilon": 1, "end_time": 1,
   "grid": "hyper_rectangle", "grid_arguments": "0, 0 : 1, 1 : true",
   "convection": "0; 0", "reaction": "0", "rhs": "0",
   "exact_solution": "x*y", "initial_value": "x*y",
   "dirichlet": "0, 1: x*y", "neumann": "2: -eps*x; 3: eps*x",
   "goals": "right = flux 1", "goals_over_time": true},
 "discretization": {"p": 1, "r": 0, "initial_refinements": 2, "n_slabs": 2},
 "study": {"mode": "dwr"}, "goal": {"kind": "scene"}, "adaptivity": {"loops": 1},
 "output": {"vtu_loops": 0, "progress": false}}
JSON
expect 0 "results:" -- run "$tmp/xy.json" --output "$tmp/xy"
/usr/bin/python3 - "$tmp/xy" <<'PY' || fail=1
import csv, sys
row = list(csv.DictReader(open(sys.argv[1] + "/loops.csv")))[-1]
J = float(list(csv.DictReader(open(sys.argv[1] + "/probes.csv")))[-1]["J_right"])
err = float(row["J_error"])
print("flux goal beside per-id Neumann data: J", J, "(exact 0.5), relative error", err)
if not (abs(J - 0.5) < 1e-10 and err < 1e-10):
    sys.exit("FAIL: the flux goal is %.12g with the error %g; expected 0.5" % (J, err))
PY
# 6. one rule for boundary ids: a Gmsh physical tag 300 takes Dirichlet data and a flux goal
cat >"$tmp/tag300.msh" <<'MSH'
$MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
4
1 0 0 0
2 1 0 0
3 1 1 0
4 0 1 0
$EndNodes
$Elements
5
1 1 2 300 300 1 2
2 1 2 300 300 2 3
3 1 2 300 300 3 4
4 1 2 300 300 4 1
5 3 2 10 10 1 2 3 4
$EndElements
MSH
expect 0 "results:" -- run "$tmp/xy.json" --output "$tmp/tag300" --set "scene.grid=" \
  --set "scene.mesh_file=$tmp/tag300.msh" --set "scene.dirichlet=300: x*y" \
  --set "scene.neumann=" --set "scene.goals=all = flux 300"
exit $fail
