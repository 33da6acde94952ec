#!/usr/bin/env bash
# Runs the whole test suite (unit, oracle, end-to-end, bounded fuzz). Select with ctest labels,
# e.g. `bash scripts/test.sh -L unit` or `-LE heavy`.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
ctest --test-dir "$BUILD_DIR" --output-on-failure -j"$(nproc)" "$@"
