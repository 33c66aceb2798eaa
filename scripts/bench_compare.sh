#!/usr/bin/env bash
# Side-by-side timing of two anisodwr binaries on the same DWR config, run back to
# back (A, B, A, B for REPEAT rounds; the minimum per phase counts), e.g. before/after
# a change:  git worktree add /tmp/old REV && build /tmp/old, then
#   scripts/bench_compare.sh /tmp/old/build/app/anisodwr build/app/anisodwr config/hemker_count.json \
#     --set adaptivity.loops=9
# Prints, per phase (primal, adjoint, estimate) summed over the loops, A's and B's
# seconds and A/B, the whole run's wall time (summary.json), and the peak memory (largest mem_peak over the loops, MB), and checks that both runs produced the same loops.csv numbers
# (all columns except the times and memory figures: mem_peak, memory_estimate_mb,
# lu_*_mb, which depend on the DoF numbering) to 1e-8 relative.
# Env: REPEAT (default 1), OUT (default results/bench_compare).
set -euo pipefail
A=$1 B=$2 CONFIG=$3
shift 3
OUT=${OUT:-results/bench_compare}
mkdir -p "$OUT"
for round in $(seq "${REPEAT:-1}"); do
  for v in A B; do
    bin=$A
    [ "$v" = B ] && bin=$B
    "$bin" run "$CONFIG" --output "$OUT/${v}_$round" --set output.vtu_loops=0 "$@" >/dev/null
  done
done
/usr/bin/python3 - "$OUT" "${REPEAT:-1}" <<'PY'
import csv, json, sys
out, repeat = sys.argv[1], int(sys.argv[2])
def load(v, r):
    return list(csv.DictReader(open(f"{out}/{v}_{r}/loops.csv")))
phases = ["t_primal", "t_adjoint", "t_estimate"]
best = {}
for v in "AB":
    for r in range(1, repeat + 1):
        rows = load(v, r)
        t = {p: sum(float(x[p]) for x in rows) for p in phases}
        t["wall"] = json.load(open(f"{out}/{v}_{r}/summary.json"))["wall_time"]
        best[v] = {p: min(best.get(v, {}).get(p, 1e300), t[p]) for p in phases + ["wall"]}
a, b = load("A", 1), load("B", 1)
same = len(a) == len(b) and all(
    abs(float(x[k]) - float(y[k])) <= 1e-8 * max(1.0, abs(float(x[k])))
    for x, y in zip(a, b) for k in x
    if not k.startswith("t_") and k not in ("mem_peak", "memory_estimate_mb", "concurrent") and not k.startswith("lu_") and x[k] != "" and y[k] != "")
print(f"{len(a)} loops, last N_tot = {a[-1]['N_tot']}; results identical: {same}")
print("| phase | A s | B s | A/B |\n|---|---|---|---|")
for p in phases:
    print(f"| {p[2:]} | {best['A'][p]:.2f} | {best['B'][p]:.2f} | {best['A'][p] / best['B'][p]:.2f} |")
print(f"| whole run (wall) | {best['A']['wall']:.2f} | {best['B']['wall']:.2f} | {best['A']['wall'] / best['B']['wall']:.2f} |")
peak = [max(float(x["mem_peak"]) for x in rows) for rows in (a, b)]
print(f"| peak MB | {peak[0]:.0f} | {peak[1]:.0f} | {peak[0] / peak[1]:.2f} |")
PY
