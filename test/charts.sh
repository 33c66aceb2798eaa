#!/usr/bin/env bash
# The chart script runs on small output directories (a 2-loop hemker_count DWR run with cells
# and cut lines, a 3-level convergence study) and writes non-empty PNG files.
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"
"$bin" run "$src/config/hemker_count.json" --output "$tmp/hemker" --set adaptivity.loops=2 \
  --set output.vtu_loops=1 >"$tmp/hemker.log" 2>&1 || { cat "$tmp/hemker.log"; exit 1; }
"$bin" run "$src/config/moving_hump_paper.json" --output "$tmp/hump" --set adaptivity.loops=2 \
  >"$tmp/hump.log" 2>&1 || { cat "$tmp/hump.log"; exit 1; }
"$bin" run "$src/config/convergence_time_r1.json" --output "$tmp/conv" --set study.levels=3 \
  >"$tmp/conv.log" 2>&1 || { cat "$tmp/conv.log"; exit 1; }
charts="/usr/bin/python3 $src/postprocess/charts.py"
$charts all "$tmp/png" "$tmp/hemker" "$tmp/hump=hump" || fail=1
$charts convergence "$tmp/png/convergence.png" "$tmp/conv/convergence.csv=dG(1)" || fail=1
$charts goal-values "$tmp/png/goals.png" "$tmp/hemker" || fail=1
$charts compare-cut "$tmp/png/compare.png" normal -1 "$tmp/hemker=a" "$tmp/hemker=b" || fail=1
$charts mesh "$tmp/png/mesh_u.png" "$tmp/hemker" 2 u -1.5 1.5 -1.5 1.5 || fail=1
# first_cell.py: one row per loop; hemker's cell at x_Gamma is cut across the layer
# after loop 1 (its normal indicator is 600 times its tangential one), so loop 2's cell
# is half as thick along the normal.
rows=$(/usr/bin/python3 "$src/postprocess/first_cell.py" "$tmp/hemker" | tail -n +3)
echo "$rows"
echo "$rows" | awk -F'|' 'NR == 1 { h1 = $4 } NR == 2 { h2 = $4 }
  END { exit !(NR == 2 && h2 > 0 && (h1 / h2 - 2) ^ 2 < 1e-4) }' \
  && echo "ok: first_cell.py" || { echo "FAIL: first_cell.py"; fail=1; }
for f in hemker_history hemker_mesh_0002 hemker_cutlines hump_history work_precision \
  convergence goals mesh_u compare; do
  png="$tmp/png/$f.png"
  if [ -s "$png" ] && [ "$(head -c 4 "$png" | tail -c 3)" = PNG ] && [ "$(stat -c %s "$png")" -gt 5000 ]; then
    echo "ok: $f.png ($(stat -c %s "$png") bytes)"
  else
    echo "FAIL: $f.png missing, empty or not a PNG"
    fail=1
  fi
done
exit $fail
