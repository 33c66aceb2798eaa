#!/usr/bin/env bash
# adaptivity.measure_time_error against a known answer: manufactured poly_space lies in
# Q2 in space, so with p = 2 the goal error of the run is temporal only (to the spatial
# solver's accuracy) and the extrapolated err_time_<goal> must equal err_<goal>, with
# the observed order 2r + 1 of dG(r) at the end point (goal u_center_T), for r = 0, 1, 2
# and SUPG on (the check keeps delta_K fixed over its three time meshes). The slab
# systems are solved directly: poly_space's coefficients depend on time, where auto
# solves by Krylov to 1e-13, and dG(2)'s errors on the finest time mesh are 4e-14.
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"

for r in 0 1 2; do
  out="$tmp/r$r"
  "$bin" run "$src/config/manufactured.json" --set scene.variant=poly_space \
    --set discretization.p=2 --set discretization.r=$r --set discretization.delta0=1 \
    --set discretization.n_slabs=16 --set study.mode=dwr --set adaptivity.loops=1 \
    --set adaptivity.theta_tau=0 --set adaptivity.measure_time_error=true \
    --set solver.type=direct --set output.vtu_loops=0 --output "$out" >/dev/null 2>&1 ||
    { echo "FAIL: r = $r: the run failed"; fail=1; continue; }
  /usr/bin/python3 - "$out/loops.csv" "$r" <<'PY' || fail=1
import csv, sys
row = list(csv.DictReader(open(sys.argv[1])))[-1]
r = int(sys.argv[2])
err, measured = float(row["err_u_center_T"]), float(row["err_time_u_center_T"])
order = float(row["err_tau_order"])
ok = abs(measured - err) <= 0.02 * abs(err) and abs(order - (2 * r + 1)) <= 0.15
print(("ok" if ok else "FAIL") + f": dG({r}): J error {err:.6e}, measured temporal error "
      f"{measured:.6e} (ratio {measured / err:.4f}, want within 2%), order {order:.3f} "
      f"(want {2 * r + 1} +- 0.15)")
sys.exit(0 if ok else 1)
PY
done

# adaptivity.time_balance: slabs are bisected only in loops with |eta_tau| >=
# time_balance (|eta_h,x| + |eta_h,y|); N_t of the next loop follows the recorded parts
for b in 0 1; do
  out="$tmp/balance$b"
  "$bin" run "$src/config/moving_hump_paper.json" --set adaptivity.loops=5 \
    --set adaptivity.theta_tau=0.5 --set adaptivity.time_balance=$b \
    --set output.vtu_loops=0 --output "$out" >/dev/null 2>&1 ||
    { echo "FAIL: time_balance = $b: the run failed"; fail=1; continue; }
  /usr/bin/python3 - "$out/loops.csv" "$b" <<'PY' || fail=1
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
b = float(sys.argv[2])
kinds = set()
for x, y in zip(rows, rows[1:]):
    refine = abs(float(x["eta_tau"])) >= b * (abs(float(x["eta_hx"])) + abs(float(x["eta_hy"])))
    n, m = int(x["N_t"]), int(y["N_t"])
    want = n + math.ceil(0.5 * n) if refine else n
    if m != want:
        sys.exit(f"FAIL: time_balance = {b}, loop {x['loop']}: N_t {n} -> {m}, want {want}")
    kinds.add(refine)
if b == 1 and kinds != {True, False}:
    sys.exit(f"FAIL: time_balance = 1 should both bisect and keep slabs in 5 loops: {kinds}")
print(f"ok: time_balance = {b}: N_t " + " ".join(r["N_t"] for r in rows))
PY
done
exit $fail
