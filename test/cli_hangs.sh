#!/usr/bin/env bash
# Exact goal values have a bounded cost: extreme layers and goals finish (or are
# refused with exit code 2) within 10 s; eps = 1e-12 starts the first loop at once.
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"
cfg=$src/config/moving_hump.json
expect_timeout=10
one=(--set adaptivity.loops=1)
expect 0 "u_xe1_T = 0.38267238893" -- run "$cfg" --output "$(o)" "${one[@]}"
expect 0 "u_xe1_T = 0.3830419" -- run "$cfg" --output "$(o)" "${one[@]}" --set scene.epsilon=1e-8
expect 0 "u_xe1_T = 0.3830955" -- run "$cfg" --output "$(o)" "${one[@]}" --set scene.epsilon=1e-12
expect 2 "exact goal value" -- run "$cfg" --output "$(o)" "${one[@]}" --set scene.epsilon=1e-300
expect 2 "goal.locations" -- run "$cfg" --output "$(o)" "${one[@]}" --set goal.kind=point --set goal.locations=5,5
expect 2 "goal.locations" -- run "$cfg" --output "$(o)" "${one[@]}" --set goal.kind=point --set goal.locations=nan,0.5
expect 2 "goal.radius" -- run "$cfg" --output "$(o)" "${one[@]}" --set goal.radius=1e6

# eps = 1e-12 starts the first loop less than a second later than the default eps
# (the exact goal values are computed before the loop header)
first_loop() { # seconds from the start to the loop table's header
  local start
  start=$(date +%s.%N)
  timeout 20 "$bin" run "$cfg" --output "$tmp/fast$1" "${one[@]}" --set scene.epsilon=$1 2>&1 |
    while IFS= read -r line; do
      [[ $line == loop* ]] && echo "$(date +%s.%N) - $start" | bc
    done
}
t6=$(first_loop 1e-6)
t12=$(first_loop 1e-12)
if [ -z "$t12" ] || (($(echo "$t12 - $t6 > 1" | bc))); then
  echo "FAIL: first loop after ${t12:-never} s with eps = 1e-12, ${t6} s with 1e-6"
  fail=1
else
  echo "ok: first loop after $t12 s with eps = 1e-12, $t6 s with 1e-6"
fi
exit $fail
