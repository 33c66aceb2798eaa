#!/usr/bin/env bash
# Installs what is missing, builds, and runs anisodwr on CONFIG (default: the moving hump).
# Usage: scripts/run.sh [CONFIG.json] [extra anisodwr run options, e.g. --set ...]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
CONFIG=${1:-$ROOT/config/moving_hump.json}
shift || true
cd "$ROOT"
"$BUILD/app/anisodwr" run "$CONFIG" "$@"
