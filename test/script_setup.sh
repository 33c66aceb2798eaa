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
