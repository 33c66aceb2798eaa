#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole test suite (ctest) in Release,
# then the unit tests once more against deal.II's Debug library (which checks much
# more: index bounds, constraint consistency, ...). Non-zero on any failure.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
(cd "$BUILD" && ctest --output-on-failure -j2)

DEBUG=${ANISODWR_DEBUG_BUILD_DIR:-$ROOT/build-debug}
if [ "${ANISODWR_SKIP_DEBUG:-0}" != 1 ]; then
  echo "== Debug build of the unit tests in $DEBUG"
  [ -f "$DEBUG/CMakeCache.txt" ] || cmake -S "$ROOT" -B "$DEBUG" -DCMAKE_BUILD_TYPE=Debug >/dev/null
  cmake --build "$DEBUG" -j2 --target test_temporal_basis test_slab test_operators test_estimator test_probes test_refinement -- --no-print-directory \
    | grep -E "error|warning" || true
  (cd "$DEBUG" && ctest --output-on-failure -j2 -R "TemporalBasis|Slab|Exactness|Lifts|Restriction|RadauReconstruction|ExactGoal|Localization|HemkerMesh|Probes|Marking|Closure")
fi
