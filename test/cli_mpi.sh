#!/usr/bin/env bash
# Runs under mpirun with 2 ranks: the DWR loops of moving_hump_paper (8 loops) and hemker
# (6 loops) reproduce the serial (1-process, UMFPACK) loops.csv: N_space, N_t equal,
# every other column (J, errors, estimates, ...) within 1e-8 relative; summary.json
# records mpi_ranks; only rank 0 prints; bad input exits 2 and a failed Krylov solve 3,
# each with one message.
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"
mpi=(mpirun --allow-run-as-root --oversubscribe -np 2)

for case in "moving_hump_paper 8" "hemker 6"; do
  set -- $case
  serial=$tmp/$1_serial parallel=$tmp/$1_mpi
  "$bin" run "$src/config/$1.json" --set adaptivity.loops="$2" --set output.vtu_loops=0 \
    --output "$serial" >/dev/null 2>&1 || { echo "FAIL: serial $1"; fail=1; continue; }
  out=$("${mpi[@]}" "$bin" run "$src/config/$1.json" --set adaptivity.loops="$2" \
    --set output.vtu_loops=0 --output "$parallel" 2>&1)
  rc=$?
  if [ "$rc" != 0 ]; then
    echo "FAIL: $1 on 2 ranks -> exit $rc: $(tail -c 400 <<<"$out")"
    fail=1
    continue
  fi
  msg=$(same_loops "$serial/loops.csv" "$parallel/loops.csv" 1e-8) || fail=1
  echo "$1, 2 ranks against 1 process: $msg"
  grep -q '"mpi_ranks": 2' "$parallel/summary.json" || { echo "FAIL: $1: no mpi_ranks 2"; fail=1; }
  grep -q '"mpi_ranks": 1' "$serial/summary.json" || { echo "FAIL: $1: no mpi_ranks 1"; fail=1; }
  [ "$(grep -c '^results:' <<<"$out")" = 1 ] || { echo "FAIL: $1: output printed by more than one rank"; fail=1; }
done

# bad input and a numerical failure: the serial exit codes, one message
out=$("${mpi[@]}" "$bin" run "$src/config/moving_hump.json" --set scene.epsilon=-1 \
  --output "$tmp/bad" 2>&1)
rc=$?
if [ "$rc" != 2 ] || [ "$(grep -c 'scene.epsilon' <<<"$out")" != 1 ]; then
  echo "FAIL: bad input on 2 ranks -> exit $rc (want 2, one message): $out"
  fail=1
fi
out=$("${mpi[@]}" "$bin" run "$src/config/moving_hump.json" --set adaptivity.loops=2 \
  --set solver.type=iterative --set solver.max_iterations=1 --set solver.fallback=none \
  --set solver.preconditioner=ilut --output "$tmp/fail" 2>&1)
rc=$?
if [ "$rc" != 3 ] || [ "$(grep -c 'did not converge' <<<"$out")" != 1 ] ||
  ! grep -q '"status": "failed: loop 1' "$tmp/fail/summary.json"; then
  echo "FAIL: failed solve on 2 ranks -> exit $rc (want 3, one message): $out"
  fail=1
fi
exit $fail
