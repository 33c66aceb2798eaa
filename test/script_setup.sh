# Sourced by the shell tests (cli_*.sh, charts.sh, fuzz_inputs.sh) with the arguments
# BIN SOURCE_DIR: sets bin, src, a temporary directory tmp removed on exit, and fail=0
# (each test sets fail=1 on a failed check and exits with it); defines expect.
set -u
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

# expect CODE PATTERN -- ARGS...: runs "$bin" ARGS (limited to expect_timeout seconds;
# 0 = no limit) and checks the exit code and that the output matches PATTERN. n counts
# the calls; o prints a fresh output directory name for the next call.
expect_timeout=0
n=0
o() { echo "$tmp/out$n"; }
expect() {
  local code=$1 pattern=$2 out rc
  shift 3
  n=$((n + 1))
  out=$(timeout "$expect_timeout" "$bin" "$@" 2>&1)
  rc=$?
  if [ "$rc" != "$code" ] || ! grep -q -- "$pattern" <<<"$out"; then
    echo "FAIL: anisodwr $* -> exit $rc (want $code; 124 = timeout), output: $(tail -c 400 <<<"$out") (want /$pattern/)"
    fail=1
  else
    echo "ok: anisodwr $* -> $rc: $(head -c 160 <<<"$out")"
  fi
}

# same_loops A.csv B.csv TOL: two loops.csv agree: the same loops, N_space, N_t, N_tot
# equal, every other column (J, errors, estimates, ...) within TOL relative (plus 1e-13
# absolute); times,
# memory figures and the concurrent flag are not compared. Prints the first differences.
same_loops() {
  /usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import csv, sys
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
bad = []
if len(a) != len(b):
    bad.append(f"{len(a)} loops against {len(b)}")
for x, y in zip(a, b):
    for k in x:
        if k.startswith("t_") or k in ("mem_peak", "memory_estimate_mb", "concurrent") or k.startswith("lu_"):
            continue
        if (x[k] == "") != (y[k] == ""):
            bad.append(f"loop {x['loop']} {k}: '{x[k]}' vs '{y[k]}'")
        elif x[k] != "":
            u, v = float(x[k]), float(y[k])
            exact = k in ("loop", "N_space", "N_t", "N_tot")
            # relative, with an absolute floor of 1e-13 for values that cancel to
            # rounding (a weighted J of +1 - 1 is 0 or 1e-16 by summation order)
            if abs(u - v) > (0 if exact else float(sys.argv[3]) * abs(u) + 1e-13):
                bad.append(f"loop {x['loop']} {k}: {u} vs {v}")
print("\n".join(bad[:10]) if bad else f"{len(a)} loops identical")
sys.exit(1 if bad else 0)
PY
}
