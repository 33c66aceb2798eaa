#!/usr/bin/env bash
# The memory estimate before each DWR loop and before a single run: a loop whose
# estimate exceeds adaptivity.max_memory_mb (or the physical memory) is not started,
# exit code 2 with a one-line message (estimate, limit, loop), summary.json status
# "stopped", the finished loops' rows on disk; loops.csv records memory_estimate_mb.
source "$(dirname "${BASH_SOURCE[0]}")/script_setup.sh" "$@"
cfg=$src/config/moving_hump_p1.json
expect_timeout=60
# 1089 DoFs on loop 1, about 1.6 times as many on loop 2: estimates well apart
# (dG(1) pinned: the messages below name it)
# theta_h = 0.6: loop 2 has about 3x loop 1's DoFs, so that the two loops' estimates
# differ by about 20 MB, well beyond the few MB the resident base varies between runs
base=(--set discretization.initial_refinements=5 --set output.vtu_loops=0 --set discretization.r=1
  --set adaptivity.theta_h=0.6)

check() { # check NAME PYTHON-ASSERTIONS (d = summary.json, rows = loops.csv rows)
  local name=$1 dir=$2 code=$3
  if python3 - "$dir" <<PY; then echo "ok: $name"; else echo "FAIL: $name"; fail=1; fi
import csv, json, sys
d = json.load(open(sys.argv[1] + "/summary.json"))
f = open(sys.argv[1] + "/loops.csv") if "$name".startswith("dwr") else None
header = f.readline().strip().split(",") if f else []
rows = list(csv.DictReader(f, fieldnames=header)) if f else []
$code
PY
}

# no limit: estimates of loops 1 and 2 recorded, the last column, below the physical memory
d=$tmp/free
expect 0 "results:" -- run "$cfg" --output "$d" "${base[@]}" --set adaptivity.loops=2
check "dwr: memory_estimate_mb per loop" "$d" '
assert "memory_estimate_mb" in header, header
e = [float(r["memory_estimate_mb"]) for r in rows]
assert len(e) == 2 and 0 < e[0] < e[1], e
assert all(float(r["mem_peak"]) > 0 for r in rows)
assert d["status"] == "ok"'

# a limit between the two estimates: loop 1 runs, loop 2 is not started
limit=$(python3 -c "import csv; e=[float(r['memory_estimate_mb']) for r in csv.DictReader(open('$d/loops.csv'))]; assert e[1]-e[0] > 12, e; print(round((e[0]+e[1])/2))")
d=$tmp/between
expect 2 "^anisodwr: stopped: loop 2: memory estimate [0-9]* MB.* exceeds adaptivity.max_memory_mb = $limit MB; N_space [0-9]*, adjoint [0-9]* DoFs, 10 slabs of dG(1), UMFPACK per temporal mode; not started$" -- \
  run "$cfg" --output "$d" "${base[@]}" --set adaptivity.loops=3 --set adaptivity.max_memory_mb=$limit
check "dwr: stopped before loop 2, loop 1 on disk" "$d" '
assert d["status"] == "stopped", d["status"]
assert d["stop_reason"].startswith("loop 2: memory estimate"), d["stop_reason"]
assert [l["loop"] for l in d["loops"]] == [1], d["loops"]
assert [r["loop"] for r in rows] == ["1"], rows
assert float(rows[0]["memory_estimate_mb"]) < '"$limit"
out=$(timeout 60 "$bin" run "$cfg" --output "$tmp/lines" "${base[@]}" --set adaptivity.max_memory_mb=$limit 2>&1 >/dev/null)
if [ "$(wc -l <<<"$out")" != 1 ]; then echo "FAIL: stderr is not one line: $out"; fail=1; fi

# a tiny limit: nothing started, summary.json and the loops.csv header written
d=$tmp/tiny
expect 2 "stopped: loop 1: memory estimate [0-9]* MB (predicted before the mesh is built: 1 coarse cells x 4^2 = 16 cells) exceeds adaptivity.max_memory_mb = 1 MB" -- \
  run "$cfg" --output "$d" --set adaptivity.max_memory_mb=1
check "dwr: stopped before loop 1" "$d" '
assert d["status"] == "stopped" and d["loops"] == [] and rows == [], (d["status"], rows)'

# an initial mesh far beyond the limit (4^14 cells of Q2) is refused before it is built:
# exit 2 within 2 s (beyond the program's start-up, timed by `anisodwr defaults`, which
# on a loaded machine itself takes seconds), peak resident memory below 500 MB,
# summary.json "stopped"
d=$tmp/huge
if python3 - "$bin" "$src/config/moving_hump.json" "$d" <<'PY'; then echo "ok: predicted mesh refused early"; else echo "FAIL: predicted mesh"; fail=1; fi
import json, resource, subprocess, sys, time
bin_, cfg, d = sys.argv[1:4]
limit = lambda: resource.setrlimit(resource.RLIMIT_AS, (4_000_000 * 1024,) * 2)
t = time.time()
subprocess.run([bin_, "defaults"], capture_output=True, check=True)
startup = time.time() - t
t = time.time()
p = subprocess.run([bin_, "run", cfg, "--output", d, "--set", "discretization.initial_refinements=14",
                    "--set", "adaptivity.max_memory_mb=2000"], capture_output=True, text=True,
                   preexec_fn=limit, timeout=60)
wall = time.time() - t
rss = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
print(f"exit {p.returncode}, {wall:.2f} s (start-up {startup:.2f} s), {rss:.0f} MB: {p.stderr.strip()}")
assert p.returncode == 2 and wall - startup < 2 and rss < 500
assert p.stderr.startswith("anisodwr: stopped: loop 1: memory estimate ")
assert "(predicted before the mesh is built: 1 coarse cells x 4^14 = 268435456 cells) exceeds adaptivity.max_memory_mb = 2000 MB" in p.stderr
assert p.stderr.count("\n") == 1
assert json.load(open(d + "/summary.json"))["status"] == "stopped"
PY

# single run and convergence study: before the run / the level
d=$tmp/single
expect 2 "stopped: run: memory estimate [0-9]* MB exceeds adaptivity.max_memory_mb = 1 MB; N_space 1089, 10 slabs of dG(1), UMFPACK per temporal mode; not started" -- \
  run "$cfg" --output "$d" --set study.mode=single --set discretization.initial_refinements=5 \
  --set adaptivity.max_memory_mb=1 --set discretization.r=1
check "single: stopped" "$d" 'assert d["status"] == "stopped" and d["levels"] == []'
# the physical memory when the key is 0: 1e6 slabs of dG(10) on 16641 DoFs would store
# 1.4 TB of slab solutions
d=$tmp/physical
expect 2 "stopped: run: memory estimate [0-9]* MB exceeds the physical memory of [0-9]* MB (adaptivity.max_memory_mb = 0); N_space 16641, 1000000 slabs of dG(10)" -- \
  run "$cfg" --output "$d" --set study.mode=single --set discretization.initial_refinements=7 \
  --set discretization.r=10 --set discretization.n_slabs=1000000
check "single: physical memory" "$d" 'assert d["status"] == "stopped" and d["levels"] == []'

# convergence study in space: levels 0 and 1 run, level 2 (four times the DoFs) is not
# started; the limit lies between the estimates of levels 1 and 2, extrapolated from a
# run of levels 0 and 1 (the data part grows more than fourfold per level)
conv=(--set study.mode=convergence --set study.refine=space --set discretization.initial_refinements=6
  --set discretization.n_slabs=2)
d=$tmp/conv2
expect 0 "results:" -- run "$cfg" --output "$d" "${conv[@]}" --set study.levels=2
limit=$(python3 -c "import json; e=[l['memory_estimate_mb'] for l in json.load(open('$d/summary.json'))['levels']]; assert e[1]-e[0] > 12, e; print(round(e[1] + 2*(e[1]-e[0])))")
d=$tmp/conv3
expect 2 "stopped: level 2: memory estimate [0-9]* MB exceeds adaptivity.max_memory_mb = $limit MB; N_space 66049," -- \
  run "$cfg" --output "$d" "${conv[@]}" --set study.levels=3 --set adaptivity.max_memory_mb=$limit
check "convergence: levels 0, 1 on disk" "$d" '
assert d["status"] == "stopped" and d["stop_reason"].startswith("level 2: memory estimate")
assert [l["level"] for l in d["levels"]] == [0, 1], d["levels"]
assert all(l["memory_estimate_mb"] > 0 for l in d["levels"])'
exit $fail
