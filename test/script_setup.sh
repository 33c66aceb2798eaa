# Sourced by the shell tests (cli_errors.sh, cli_solver.sh, charts.sh) with the
# arguments BIN SOURCE_DIR: sets bin, src, a temporary directory tmp removed on exit,
# and fail=0 (each test sets fail=1 on a failed check and exits with it).
set -u
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
