#!/usr/bin/env bash
# Shared by run.sh and test.sh: installs missing Debian packages (idempotent) and
# configures + builds anisodwr in Release into build/. Usage: source scripts/setup.sh
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# libopenblas0-pthread replaces the reference BLAS/LAPACK (update-alternatives) under
# UMFPACK, MUMPS and LAPACK: UMFPACK factorizes 2.6-4.4x faster (doc/results.md).
PACKAGES="libdeal.ii-dev libmumps-dev openmpi-bin libopenblas0-pthread libgtest-dev cmake g++ make ninja-build ccache python3-matplotlib"

missing=""
for p in $PACKAGES; do
  dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "== installing Debian packages:$missing (deal.II takes ~2 minutes)"
  SUDO=""
  [ "$(id -u)" = 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing >/dev/null
fi

# On a CI machine (CI=true) the build starts from an empty ccache: every lookup misses,
# and hashing the precompiled header per file made the fresh Release build 191 s against
# 153-168 s without ccache.
if [ "${CI:-}" = true ]; then export CCACHE_DISABLE=1; fi
BUILD=${ANISODWR_BUILD_DIR:-$ROOT/build}
# The library compiles as unity batches of 7 sources (about a minute less on a fresh
# clone; ANISODWR_UNITY=0 configures one object per source, for editing a few files).
UNITY=ON
[ "${ANISODWR_UNITY:-1}" = 0 ] && UNITY=OFF
# New build directories use Ninja: it starts a test's sources while the library's last
# unity batches still compile, where make waits for the whole library target (the checked
# build of scripts/test.sh in a fresh clone: 308 s against 344 s). An existing directory
# keeps its generator. generator_for DIR prints the -G option for a new DIR.
generator_for() { [ -f "$1/CMakeCache.txt" ] || echo "-GNinja"; }
if [ ! -f "$BUILD/CMakeCache.txt" ]; then
  echo "== configuring (Release) in $BUILD"
  cmake -S "$ROOT" -B "$BUILD" $(generator_for "$BUILD") -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_UNITY_BUILD=$UNITY -DCMAKE_UNITY_BUILD_BATCH_SIZE=7 >/dev/null
fi
echo "== building (-j2)"
start=$(date +%s)
cmake --build "$BUILD" -j2 | grep -E "error|warning|Linking" || true
test -x "$BUILD/app/anisodwr" || { echo "build failed" >&2; exit 1; }
echo "== build: $(($(date +%s) - start)) s"
