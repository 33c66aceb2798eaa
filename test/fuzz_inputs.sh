#!/usr/bin/env bash
# Fuzz corpus of bad inputs: every --set line and every config file generated here must
# give exit code 2 within 10 s and a message naming the key (or the file).
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"
cfg=$src/config/moving_hump.json
count=0
check() { # check PATTERN -- args...
  local pattern=$1 out rc
  shift 2
  count=$((count + 1))
  out=$(timeout 10 "$bin" run "$@" --output "$tmp/o$count" --set adaptivity.loops=1 2>&1)
  rc=$?
  if [ "$rc" != 2 ] || ! grep -qF -- "$pattern" <<<"$out"; then
    echo "FAIL: $* -> exit $rc (want 2 naming '$pattern'): $(tail -c 300 <<<"$out")"
    fail=1
  fi
}
# bad values per key: integers, reals, choices, booleans
ints="discretization.p discretization.r discretization.initial_refinements discretization.n_slabs
  study.levels adaptivity.loops adaptivity.adjoint_degree solver.restart solver.max_iterations"
reals="scene.epsilon scene.end_time discretization.delta0 solver.tolerance solver.ilu_fill
  adaptivity.theta_h adaptivity.theta_tau adaptivity.theta_coarsen adaptivity.tolerance
  goal.radius solver.auto_threshold adaptivity.max_dofs"
choices="scene.name discretization.supg_length solver.type solver.krylov solver.preconditioner
  solver.fallback study.mode study.refine goal.kind adaptivity.mode adaptivity.marking
  adaptivity.tolerance_measure"
bools="solver.reuse_factorization goal.over_time output.progress"
for k in $ints; do
  for v in -1 abc 1.5 99999999999 '' nan; do check "$k" -- "$cfg" --set "$k=$v"; done
done
for k in $reals; do
  for v in -1 abc nan inf 1e999 '' 1,2; do check "$k" -- "$cfg" --set "$k=$v"; done
done
for k in scene.epsilon scene.end_time; do check "$k" -- "$cfg" --set "$k=0"; done
# numbers that underflow double precision: subnormal (1e-320, 4.9e-324) or rounded to 0
for k in $reals; do
  for v in 1e-320 4.9e-324 1e-400; do
    check "for key '$k': it underflows double precision" -- "$cfg" --set "$k=$v"
  done
done
for v in '0.5,1e-320' '4.9e-324,0.5'; do
  check "in key 'goal.locations': " -- "$cfg" --set goal.kind=point --set "goal.locations=$v"
done
check "in key 'goal.weights': '1e-400' underflows" -- "$cfg" --set goal.weights=1e-400
# bounded ranges and combinations of solver keys the slab solvers refuse
for v in -0.01 1.5; do check "'adaptivity.kappa'; expected a fraction in [0, 1]" -- "$cfg" --set "adaptivity.kappa=$v"; done
for v in 10.5 30 1e300; do check "'solver.ilu_fill'; expected a number with 0 <= v <= 10" -- "$cfg" --set "solver.ilu_fill=$v"; done
for type in iterative auto; do
  check "invalid combination solver.type = $type, solver.krylov = bicgstab, solver.inner_iterations = 5" \
    -- "$cfg" --set solver.type=$type --set solver.krylov=bicgstab --set solver.inner_iterations=5
done
for k in adaptivity.theta_h adaptivity.theta_tau adaptivity.theta_coarsen; do
  check "$k" -- "$cfg" --set "$k=1.01"
done
for k in $choices; do
  for v in bogus '' 'dwr ' 42; do check "$k" -- "$cfg" --set "$k=$v"; done
done
for k in $bools; do
  for v in maybe 2 ''; do check "$k" -- "$cfg" --set "$k=$v"; done
done
for k in scene.epsilonn sceen.name discretization.q goal.location output.dir; do
  check "${k%%.*}" -- "$cfg" --set "$k=1"
done
# goals
for loc in '5,5' '-0.1,0.5' 'nan,0.5' '0.5' '0.5,0.5,0.5' 'a,b' '0.5,inf' '0.5,0.5; 2,2' ';'; do
  check "goal.locations" -- "$cfg" --set goal.kind=point --set "goal.locations=$loc"
done
for loc in '2,2,3,3' '0.5,0.5,0.2,0.9' '0,0,1' '-1,0,0.5,0.5' '0,0,1,1.5' 'x,0,1,1'; do
  check "goal.locations" -- "$cfg" --set goal.kind=mean --set "goal.locations=$loc"
done
for loc in '0,0' '20,20' '0.5,0.5'; do
  check "goal.locations" -- "$src/config/hemker.json" --set goal.kind=point --set "goal.locations=$loc"
done
# flux goals: a Neumann id, an id not in the mesh, no id, a non-integer, at T
for loc in '2' '1,9' '' '1.5' 'x'; do
  check "goal.locations" -- "$src/config/hemker.json" --set goal.kind=flux \
    --set goal.over_time=true --set goal.reference= --set "goal.locations=$loc"
done
check "goal.over_time" -- "$src/config/hemker.json" --set goal.kind=flux --set goal.reference= \
  --set goal.locations=1
for w in 'a' '1,2,3' 'nan' '1,,2'; do check "goal.weights" -- "$cfg" --set "goal.weights=$w"; done
# config files
i=0
while IFS= read -r text; do
  i=$((i + 1))
  printf '%s' "$text" >"$tmp/c$i.json"
  check "c$i.json" -- "$tmp/c$i.json"
done <<'CORPUS'
null
42
"hello"
[1, 2]
[]
true
{
{"scene": }
{"scene": {"epsilon": 1e-6}
{"scene": 5}
{"scene": [1, 2]}
{"scene": {"epsilon": [1]}}
{"scene": {"epsilon": {"a": 1}}}
{"scene": {"epsilon": -1}}
{"scene": {"name": "nope"}}
{"scenery": {"name": "heat"}}
{"scene": {"epsilonn": 1}}
{"discretization": {"p": 0}}
{"discretization": {"r": "x"}}
{"adaptivity": {"theta_h": 2}}
{"goal": {"radius": -1}}
{"study": {"mode": "dwr"}, "goal": {"kind": "point", "locations": "9,9"}}
{"a": {"b": {"c": {}}}}
{"scene": {"epsilon": 1e-6}} trailing
{"scene": {"epsilon": 1e-320}}
{"scene": {"end_time": 4.9e-324}}
{"discretization": {"delta0": 1e-400}}
{"study": {"mode": "dwr"}, "goal": {"kind": "point", "locations": "0.5, 1e-320"}}
{"scene": {"variant": "a\u0000b"}}
{"scene\u0000x": {"name": "heat"}}
{"scene": {"na\u0000me": "heat"}}
{"scenery": {}}
{"goal": ""}
{"goal": []}
{"adaptivity": {"kappa": -0.01}}
{"solver": {"ilu_fill": 30}}
{"solver": {"type": "auto", "krylov": "bicgstab", "inner_iterations": 5}}
CORPUS
python3 -c "print('{\"a\": ' * 5000)" >"$tmp/deep.json"
check "deep.json" -- "$tmp/deep.json"
python3 -c "print('{\"a\": [' + '[' * 100000)" >"$tmp/deep2.json"
check "deep2.json" -- "$tmp/deep2.json"
check "$tmp" -- "$tmp"
check "missing.json" -- "$tmp/missing.json"
# the custom scene (scene.name = custom): expressions, boundary ids, mesh files, data
mesh=$src/config/custom_mesh.json
example=$src/config/custom_example.json
for v in 'sin(x' 'x+' '2*' 'x y' 'q' '(1' 'sin()' '1/' ''; do
  check "scene.rhs" -- "$mesh" --set "scene.rhs=$v"
done
# muparser would take these: the last of several values, an assignment
check "'1, 2' for key 'scene.rhs': it has 2 comma-separated values" -- "$mesh" --set "scene.rhs=1, 2"
check "'x = 3' for key 'scene.rhs': '=' at position 2 assigns" -- "$mesh" --set "scene.rhs=x = 3"
check "for key 'scene.dirichlet': '=' at position" -- "$mesh" \
  --set "scene.dirichlet=1: y = x; 4: 1"
# data that are not finite somewhere on the domain: the key, the expression and a point
for v in '1/0' 'sqrt(-1)' 'log(0)' '1e308*x'; do
  check "key 'scene.rhs': the expression '$v' is" -- "$mesh" --set "scene.rhs=$v"
done
check "key 'scene.rhs': the expression '1/(x-0.5)' is infinite at (x, y, t) = (0.5," -- \
  "$example" --set "scene.rhs=1/(x-0.5)"
check "key 'scene.dirichlet': the expression ' log(y)' is infinite" -- "$mesh" \
  --set "scene.dirichlet=1: log(y); 4: 1"
check "scene.reaction" -- "$mesh" --set "scene.reaction=nx"
check "scene.initial_value" -- "$mesh" --set "scene.initial_value=u"
check "scene.neumann" -- "$mesh" --set "scene.neumann=2, 3: nz"
check "scene.convection" -- "$mesh" --set "scene.convection=1; 2; 3"
check "scene.constants" -- "$mesh" --set "scene.constants=x = 1"
check "scene.constants" -- "$mesh" --set "scene.constants=a = 1, a = 2"
check "scene.constants" -- "$mesh" --set "scene.constants=a = b"
check "scene.dirichlet" -- "$mesh" --set "scene.dirichlet=4: 1"
check "scene.dirichlet" -- "$mesh" --set "scene.dirichlet=1, 4, 9: 1"
check "scene.dirichlet" -- "$mesh" --set "scene.dirichlet=a: 1"
check "scene.dirichlet" -- "$mesh" --set "scene.dirichlet=1: 0; 4: 1; 2: 0"
check "scene.mesh_file" -- "$mesh" --set "scene.mesh_file=missing.msh"
check "scene.mesh_file" -- "$mesh" --set "scene.mesh_file=$tmp"
check "scene.mesh_file" -- "$mesh" --set "scene.mesh_file=$src/README.md"
check "scene.grid" -- "$example" --set "scene.grid_arguments=0 : 1"
check "scene.manifolds" -- "$mesh" --set "scene.manifolds=boundary 9: polar 0, 0"
check "scene.manifolds" -- "$mesh" --set "scene.manifolds=cells 10: polar 0"
# a constant's name longer than muparser takes: blamed on scene.constants, not on the first
# expression that uses the constants
check "(a name of 20000 characters) in key 'scene.constants'" -- "$example" \
  --set "scene.constants=$(printf 'a%.0s' $(seq 20000)) = 2"
# the default goal point in a hole: the cause, not a radius
check "key 'scene.goals': goal u_center_T is centred at (0, 0), outside the domain" -- "$example" \
  --set scene.grid=hyper_shell --set "scene.grid_arguments=0, 0 : 0.5 : 1 : 8 : true" \
  --set "scene.dirichlet=0, 1: 0" --set scene.neumann= --set scene.exact_solution= --set scene.goals=
# an exact flux on a curved boundary: the key and its source
check "key 'scene.goals': goal 'f' (a flux through boundary id 4, which is curved" -- \
  "$src/config/custom_hemker.json" --set "scene.exact_solution=x" --set "scene.rhs=1" \
  --set "scene.dirichlet=1, 4: x" --set "scene.neumann=2: eps; 3: 0" --set "scene.initial_value=x" \
  --set "scene.goals=f = flux 4" --set goal.reference=
# polar cells about a wrong centre bend straight walls into spirals
check "is neither an arc about" -- "$mesh" --set "scene.manifolds=cells 10: polar 5, 5"
# repetitions that deal.II reads as 2^32 - 1 or as the first of two (memory), and a
# domain whose areas overflow (the goal quadrature then never ends)
for reps in '-1, 1' '4' '1, 0' '2000, 2000'; do
  check "key 'scene.grid_arguments'" -- "$example" --set scene.grid=subdivided_hyper_rectangle \
    --set "scene.grid_arguments=$reps : 0, 0 : 1, 1 : true"
done
check "key 'scene.grid_arguments'" -- "$example" --set scene.grid=subdivided_hyper_cube \
  --set "scene.grid_arguments=-3 : 0 : 1"
check "beyond 1e8 in size" -- "$example" --set scene.grid=hyper_rectangle \
  --set "scene.grid_arguments=0, 0 : 1e300, 1e300 : true"
check "scene.manifolds" -- "$mesh" --set "scene.manifolds=faces 4: transfinite"
check "scene.manifolds" -- "$example" --set "scene.manifolds=cells 0: transfinite"
check "scene.goals" -- "$mesh" --set "scene.goals=point 9, 9"
check "scene.goals" -- "$mesh" --set "scene.goals=mean 0, 0, 3, 1"
check "scene.goals" -- "$mesh" --set "scene.goals=line 0, 0"
check "scene.rhs" -- "$example" --set "scene.rhs=exp(-t)"
check "scene.neumann" -- "$example" --set "scene.neumann=2, 3: 0"
check "scene.initial_value" -- "$example" --set "scene.initial_value=1"
# broken Gmsh files (format 2.2): msh NAME NODES ELEMENTS writes $tmp/NAME.msh; each
# node line "tag x y", each element line "type tag nodes..." (1 line, 2 triangle, 3 quad)
msh() {
  local f=$tmp/$1.msh n e
  n=$(grep -c . <<<"$2")
  e=$(grep -c . <<<"$3")
  {
    printf '$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%s\n' "$n"
    awk '{print $1, $2, $3, 0}' <<<"$2"
    printf '$EndNodes\n$Elements\n%s\n' "$e"
    awk '{printf "%d %d 2 %d %d", NR, $1, $2, $2; for (i = 3; i <= NF; ++i) printf " %s", $i; print ""}' <<<"$3"
    printf '$EndElements\n'
  } >"$f"
  echo "$f"
}
square="1 0 0
2 1 0
3 1 1
4 0 1"
two="1 0 0
2 1 0
3 2 0
4 0 1
5 1 1
6 2 1"
# a problem that runs on any of these meshes (all boundary faces have id 0)
onmesh=$tmp/onmesh.json
cat >"$onmesh" <<'JSON'
{"scene": {"name": "custom", "epsilon": 0.01, "end_time": 1, "mesh_file": "none.msh",
   "convection": "1; 0", "reaction": "0", "rhs": "1", "initial_value": "0",
   "dirichlet": "0: 0", "goals": "point 0.5, 0.5", "goals_over_time": true},
 "discretization": {"p": 1, "r": 0, "initial_refinements": 1, "n_slabs": 2},
 "study": {"mode": "dwr"}, "goal": {"kind": "scene"}, "output": {"progress": false}}
JSON
mesh=$onmesh
check "cells that are not quadrilaterals (triangles)" -- "$mesh" --set "scene.mesh_file=$(msh tri "$square" "2 10 1 2 3
2 10 1 3 4")"
check "cells that are not quadrilaterals (triangles)" -- "$mesh" --set "scene.mesh_file=$(msh mixed "$two" "3 10 1 2 5 4
2 10 2 3 6
2 10 2 6 5")"
# a crack: the right cell has its own nodes 7, 8 at the points of 2 and 5
check "has two nodes at the point (1, 0)" -- "$mesh" --set "scene.mesh_file=$(msh crack "$two
7 1 0
8 1 1" "3 10 1 2 5 4
3 10 7 3 6 8")"
# a hanging coarse node: node 7 = (1, 0.5) in the left edge of the two right cells only
check "inside the boundary edge from (1, 0) to (1, 1)" -- "$mesh" --set "scene.mesh_file=$(msh hanging "$two
7 1 0.5
8 2 0.5" "3 10 1 2 5 4
3 10 2 3 8 7
3 10 7 8 6 5")"
check "the node 2 is defined twice" -- "$mesh" --set "scene.mesh_file=$(msh twice "$two
2 1.5 0" "3 10 1 2 5 4
3 10 2 3 6 5")"
# structure: a format-4 header over a format-2 body (deal.II's reader allocated without
# bound), a wrong element count, an element node $Nodes does not define
f=$(msh v4head "$square" "3 10 1 2 3 4")
sed -i 's/^2\.2 0 8$/4.1 0 8/' "$f"
check "format 4 needs an \$Entities section" -- "$mesh" --set "scene.mesh_file=$f"
f=$(msh count "$square" "3 10 1 2 3 4")
sed -i '/^\$Elements$/{n;s/.*/3/}' "$f"
check "\$Elements: entry 2, the element number: '\$EndElements' is not a whole number" -- "$mesh" --set "scene.mesh_file=$f"
check "\$Elements: entry 1 refers to node 9, which \$Nodes does not define" -- "$mesh" --set "scene.mesh_file=$(msh undefined "$square" "3 10 1 2 3 9")"
# a bow-tie (nodes 3 and 4 swapped) and a cell of zero area (all nodes on a line)
check "has zero area, crossed edges or the wrong orientation" -- "$mesh" --set "scene.mesh_file=$(msh bowtie "$square" "3 10 1 2 4 3")"
check "has zero area, crossed edges or the wrong orientation" -- "$mesh" --set "scene.mesh_file=$(msh flat "1 0 0
2 1 0
3 2 0
4 3 0" "3 10 1 2 3 4")"
mesh=$src/config/custom_mesh.json
# (deal.II's debug build refuses the radii itself)
check "scene.grid" -- "$example" --set scene.grid=hyper_shell --set "scene.grid_arguments=0, 0 : 2 : 1 : 8 : true"
# goal names: twice, given or default (the columns of loops.csv and probes.csv)
check "goal name 'a' appears twice in key 'scene.goals'" -- "$mesh" \
  --set "scene.goals=a = point 2, 0.5; a = point 2.5, 0.5"
check "goal name 'point_2' appears twice in key 'scene.goals'" -- "$mesh" \
  --set "scene.goals=point_2 = point 2, 0.5; point 2.5, 0.5"
check "goal name 'a' appears twice in key 'goal.locations'" -- "$cfg" --set goal.kind=point \
  --set "goal.locations=a = 0.5, 0.5; a = 0.6, 0.6"
echo "$count bad inputs checked"
[ "$count" -ge 100 ] || { echo "FAIL: corpus smaller than 100"; fail=1; }
exit $fail
