#!/usr/bin/env bash
# Every class of bad input gives exit code 2 and a message naming the key/file/value.
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"


cfg=$src/config/moving_hump.json
printf '{ "scene": { "name": "moving_hump", ' >"$tmp/broken.json"
printf '{ "discretization": { "pp": 2 } }' >"$tmp/typo.json"
printf '{ "scenery": { "name": "heat" } }' >"$tmp/section.json"

expect 2 "nonexistent.json" -- run "$tmp/nonexistent.json"
expect 2 "invalid JSON" -- run "$tmp/broken.json"
expect 2 "discretization.pp.*did you mean 'p'" -- run "$tmp/typo.json"
expect 2 "unknown section 'scenery'" -- run "$tmp/section.json"
expect 2 "scene.epsilon" -- run "$cfg" --set scene.epsilon=0
expect 2 "scene.epsilon" -- run "$cfg" --set scene.epsilon=-1
expect 2 "scene.epsilon.*0 < v <= 1e6" -- run "$cfg" --set scene.epsilon=1e300
expect 2 "scene.end_time.*0 < v <= 1e6" -- run "$cfg" --set scene.end_time=1.7e308
expect 2 "discretization.r" -- run "$cfg" --set discretization.r=-1
expect 2 "discretization.p" -- run "$cfg" --set discretization.p=abc
expect 2 "scene.name" -- run "$cfg" --set scene.name=hemkerr
expect 2 "scene.variant" -- run "$cfg" --set scene.name=heat --set scene.variant=cubic
expect 2 "section.key=value" -- run "$cfg" --set epsilon
expect 2 "unknown option" -- run "$cfg" --bogus
expect 2 "unknown command" -- frobnicate
expect 2 "goal.weights" -- run "$cfg" --set study.mode=dwr --set goal.weights=1,2,3
expect 2 "goal.locations" -- run "$cfg" --set study.mode=dwr --set goal.kind=point --set goal.locations=0.5
expect 2 "goal.locations" -- run "$cfg" --set study.mode=dwr --set goal.kind=mean --set goal.locations="0.5,0.5,0.2,0.9"
expect 2 "adaptivity.theta_h" -- run "$cfg" --set adaptivity.theta_h=1.5
expect 2 "adaptivity.mode" -- run "$cfg" --set adaptivity.mode=random
expect 0 "anisodwr run" -- --help
# Without an exact solution the convergence study prints no error columns (the CSV
# leaves them empty): hemker, one level.
expect 0 "level 0: N_space" -- run "$src/config/hemker.json" --output "$tmp/hk" \
  --set study.mode=convergence --set study.levels=1 --set discretization.initial_refinements=0 \
  --set discretization.n_slabs=2 --set output.vtu_every=0 --set output.progress=false
if "$bin" run "$src/config/hemker.json" --output "$tmp/hk" --set study.mode=convergence \
  --set study.levels=1 --set discretization.initial_refinements=0 \
  --set discretization.n_slabs=2 --set output.vtu_every=0 --set output.progress=false 2>&1 |
  grep -q "err_L2_T"; then
  echo "FAIL: hemker convergence study prints err_L2_T without an exact solution"
  fail=1
fi

# `defaults` prints a config that loads and runs.
"$bin" defaults >"$tmp/defaults.json" || fail=1
expect 0 "results:" -- run "$tmp/defaults.json" --output "$tmp/out" --set output.vtu_every=0 \
  --set output.progress=false
[ -s "$tmp/out/summary.json" ] || { echo "FAIL: no summary.json"; fail=1; }
exit $fail
