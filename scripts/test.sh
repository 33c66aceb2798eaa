#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (ctest) in Release,
# then one checked build: against deal.II's Debug library (which checks much more: index
# bounds, constraint consistency, ...) and with AddressSanitizer + UndefinedBehaviorSanitizer,
# the unit tests, the memory estimate's tests and two DWR loops of the moving hump.
# Non-zero on any failure. ANISODWR_SKIP_DEBUG=1 skips the checked stage;
# ANISODWR_SKIP_SANITIZERS=1 builds it without the sanitizers.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"

# run_gtests DIR FILTER EXPECTED BINARY...: runs each gtest executable of DIR/test whole
# (the cases matching FILTER), two at a time, and checks that EXPECTED cases ran. ctest
# starts a process per case, and each process spends ~0.4 s (Release; ~0.9 s in the
# checked build) loading deal.II's library and its dependencies: 112 checked cases (-O1) took
# 83 s through ctest and 32 s so. `ctest -R NAME` still runs single cases.
run_gtests() {
  local dir=$1 filter=$2 expected=$3 logs status=0 ran
  shift 3
  logs=$(mktemp -d)
  printf '%s\n' "$@" | xargs -P2 -I{} bash -c 'cd "$0/test" && ./{} --gtest_filter="$1" >"$2/{}.log" 2>&1 || { echo "FAILED: $0/test/{}:"; tail -n 60 "$2/{}.log"; exit 1; }' \
    "$dir" "$filter" "$logs" || status=1
  ran=$(cat "$logs"/*.log | grep -c '^\[ RUN      \]' || true)
  { grep -h '^\[  PASSED  \]\|^\[  SKIPPED \]\|^\[  FAILED  \]' "$logs"/*.log || true; } | sort | uniq -c
  rm -rf "$logs"
  if [ "$ran" != "$expected" ]; then
    echo "gtest executables ran $ran cases; ctest lists $expected" >&2
    status=1
  fi
  return $status
}
# ctest's count of the tests with a label (and a name matching ctest -R REGEX)
count_tests() { (cd "$1" && ctest -N "${@:2}" | sed -n 's/^Total Tests: //p'); }

start=$(date +%s)
all=$(count_tests "$BUILD")
scripts=$(count_tests "$BUILD" -L script)
cases=$(count_tests "$BUILD" -L gtest)
if [ $((scripts + cases)) != "$all" ]; then
  echo "test/CMakeLists.txt: $all tests, but $scripts labelled script and $cases gtest" >&2
  exit 1
fi
(cd "$BUILD" && ctest --output-on-failure -j2 -L script)
# the gtest executables, the longest first
binaries=$(cd "$BUILD/test" && for b in test_regression test_iterative test_goals; do
  [ -x "$b" ] && echo "$b"; done; find . -maxdepth 1 -type f -executable -name 'test_*' -printf '%f\n' | sort |
  grep -vx 'test_regression\|test_iterative\|test_goals')
run_gtests "$BUILD" '*' "$cases" $binaries
echo "== Release tests ($scripts scripts through ctest, $cases gtest cases): $(($(date +%s) - start)) s"

# the unit tests the checked stage runs (targets; test names, ctest -R)
UNIT_TARGETS="test_temporal_basis test_slab test_operators test_estimator test_probes test_refinement
  test_custom_scene test_memory"
UNIT_TESTS="TemporalBasis|Slab|Exactness|Lifts|Restriction|RadauReconstruction|ExactGoal|Localization|Estimator|ShortVectors|HemkerMesh|Probes|Marking|Closure|CustomScene|SeparateInTime|StabilizationTerms|MemoryEstimate"

# One build checks both ways: deal.II's Debug library (its Assert()s) and the sanitizers
# (-O0 -g1 after the Debug flags, CMakeLists.txt). The library compiles as unity sources
# (batches of 7 files): the deal.II headers are parsed once per batch, not once per file.
CHECKED=${ANISODWR_DEBUG_BUILD_DIR:-$ROOT/build-debug}
SANITIZE=ON
[ "${ANISODWR_SKIP_SANITIZERS:-0}" = 1 ] && SANITIZE=OFF
if [ "${ANISODWR_SKIP_DEBUG:-0}" != 1 ]; then
  echo "== Debug build (deal.II's Debug library, sanitizers $SANITIZE) of the unit tests and anisodwr in $CHECKED"
  start=$(date +%s)
  cmake -S "$ROOT" -B "$CHECKED" $(generator_for "$CHECKED") -DCMAKE_BUILD_TYPE=Debug \
    -DANISODWR_SANITIZE=$SANITIZE -DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=7 >/dev/null
  cmake --build "$CHECKED" -j2 --target anisodwr_app $UNIT_TARGETS | grep -E "error|warning" || true
  test -x "$CHECKED/app/anisodwr" || { echo "Debug build failed" >&2; exit 1; }
  echo "== Debug build: $(($(date +%s) - start)) s"
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1
  export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
  run_gtests "$CHECKED" "*${UNIT_TESTS//|/*:*}*" "$(count_tests "$CHECKED" -L gtest -R "$UNIT_TESTS")" \
    $UNIT_TARGETS
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
  echo "== two DWR loops of config/moving_hump.json, Debug library and sanitizers"
  "$CHECKED/app/anisodwr" run "$ROOT/config/moving_hump.json" --output "$out" \
    --set adaptivity.loops=2 --set output.progress=false | tail -n 3
  echo "== Debug stage: $(($(date +%s) - start)) s"
fi
