#!/usr/bin/env bash
# The main job on the bundled default input (grows with the product).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${1:-build}
OUT=${OUT:-out/main}
mkdir -p "$OUT"
echo "== main job: (not yet defined)"
