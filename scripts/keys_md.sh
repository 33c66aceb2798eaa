#!/usr/bin/env bash
# Regenerates doc/keys.md (the full key reference) from `anisodwr defaults`.
# Usage: scripts/keys_md.sh [--check] [ANISODWR_BINARY]   (default build/app/anisodwr)
#   --check: write into a temporary file and fail (exit 1, with the diff) when doc/keys.md differs.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
bin=${1:-$ROOT/build/app/anisodwr}
tmp=$(mktemp)
trap 'rm -f "$tmp"' EXIT
"$bin" defaults | /usr/bin/python3 "$ROOT/postprocess/keys_md.py" > "$tmp"
if [ "$check" = 1 ]; then
  if ! diff -u "$ROOT/doc/keys.md" "$tmp"; then
    echo "doc/keys.md is stale: run scripts/keys_md.sh" >&2
    exit 1
  fi
else
  cp "$tmp" "$ROOT/doc/keys.md"
  echo "wrote doc/keys.md"
fi
