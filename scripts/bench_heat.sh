#!/usr/bin/env bash
# Per-slab overhead on the heat problem with exactly the work of a cG(1)-dG(1) step-1
# type run: 64x64 cells, 100 slabs, 845,000 space-time DoFs. Usage:
#   scripts/bench_heat.sh [BINARY ...]   (default: build/app/anisodwr; several binaries
#   are compared side by side, ratios against the first)
# Prints a Markdown table: process wall time (best of 3), the march (slab loop) and its
# solve / factorize parts, the rest of the run (error evaluation, output) from
# summary.json, and the L2(L2) error (identical for every binary).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bins=("$@")
[ ${#bins[@]} -gt 0 ] || bins=(build/app/anisodwr)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| binary | process s (best of 3) | march s | solve s | factorize s | rest s | err_L2L2 | process ratio |"
echo "|---|---|---|---|---|---|---|---|"
first=""
for b in "${bins[@]}"; do
  best=""
  for i in 1 2 3; do
    rm -rf "$out/run"
    s=$(date +%s.%N)
    "$b" run config/heat.json --set discretization.p=1 --set discretization.initial_refinements=6 \
      --set discretization.n_slabs=100 --set output.vtu_every=0 --output "$out/run" >/dev/null
    e=$(date +%s.%N)
    t=$(python3 -c "print($e - $s)")
    best=$(python3 -c "print(min($t, ${best:-1e9}))")
    [ "$best" = "$t" ] && cp "$out/run/summary.json" "$out/best.json"
  done
  [ -n "$first" ] || first=$best
  python3 - "$out/best.json" "$b" "$best" "$first" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); lv = d["levels"][0]; w = lv["wall_time"]
best, first = float(sys.argv[3]), float(sys.argv[4])
print(f"| {sys.argv[2]} | {best:.2f} | {w['total']:.3f} | {w['solve']:.3f} | {w['factorize']:.3f} | "
      f"{d['wall_time'] - w['total']:.3f} | {lv['err_L2L2']:.6e} | {first / best:.2f} |")
PY
done
