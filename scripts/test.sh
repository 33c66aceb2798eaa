#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (ctest) in Release,
# then the unit tests once more against deal.II's Debug library (which checks much
# more: index bounds, constraint consistency, ...), then the unit tests and a short DWR
# run built with AddressSanitizer + UndefinedBehaviorSanitizer. Non-zero on any failure.
# ANISODWR_SKIP_DEBUG=1 / ANISODWR_SKIP_SANITIZERS=1 skip the last two stages.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
start=$(date +%s)
(cd "$BUILD" && ctest --output-on-failure -j2)
echo "== Release tests: $(($(date +%s) - start)) s"

# the unit tests both extra stages run (test names, ctest -R)
UNIT_TARGETS="test_temporal_basis test_slab test_operators test_estimator test_probes test_refinement
  test_custom_scene"
UNIT_TESTS="TemporalBasis|Slab|Exactness|Lifts|Restriction|RadauReconstruction|ExactGoal|Localization|Estimator|ShortVectors|HemkerMesh|Probes|Marking|Closure|CustomScene|SeparateInTime"
# Both extra builds compile the library as unity sources (batches of 7 files): the
# deal.II headers are parsed once per batch rather than once per file.
UNITY="-DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=7"

DEBUG=${ANISODWR_DEBUG_BUILD_DIR:-$ROOT/build-debug}
if [ "${ANISODWR_SKIP_DEBUG:-0}" != 1 ]; then
  echo "== Debug build of the unit tests in $DEBUG"
  start=$(date +%s)
  cmake -S "$ROOT" -B "$DEBUG" -DCMAKE_BUILD_TYPE=Debug $UNITY >/dev/null
  cmake --build "$DEBUG" -j2 --target $UNIT_TARGETS -- --no-print-directory \
    | grep -E "error|warning" || true
  (cd "$DEBUG" && ctest --output-on-failure -j2 -R "$UNIT_TESTS")
  echo "== Debug stage: $(($(date +%s) - start)) s"
fi

# AddressSanitizer (with leak detection) and UBSan, against deal.II's release library:
# the unit tests, the memory estimate's tests and two DWR loops of the moving hump.
ASAN=${ANISODWR_ASAN_BUILD_DIR:-$ROOT/build-asan}
if [ "${ANISODWR_SKIP_SANITIZERS:-0}" != 1 ]; then
  echo "== AddressSanitizer + UBSan build of the unit tests and anisodwr in $ASAN"
  start=$(date +%s)
  cmake -S "$ROOT" -B "$ASAN" -DCMAKE_BUILD_TYPE=Release -DANISODWR_SANITIZE=ON $UNITY >/dev/null
  cmake --build "$ASAN" -j2 --target anisodwr_app $UNIT_TARGETS test_memory -- --no-print-directory \
    | grep -E "error|warning" || true
  test -x "$ASAN/app/anisodwr" || { echo "sanitizer build failed" >&2; exit 1; }
  echo "== sanitizer build: $(($(date +%s) - start)) s"
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1
  export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
  (cd "$ASAN" && ctest --output-on-failure -j2 -R "$UNIT_TESTS|MemoryEstimate")
  out=$(mktemp -d)
  trap 'rm -rf "$out"' EXIT
  echo "== two DWR loops of config/moving_hump.json under the sanitizers"
  "$ASAN/app/anisodwr" run "$ROOT/config/moving_hump.json" --output "$out" \
    --set adaptivity.loops=2 | tail -n 3
  echo "== sanitizer stage: $(($(date +%s) - start)) s"
fi
