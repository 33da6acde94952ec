#!/usr/bin/env bash
# The bad-input table (tests/bad_inputs.cpp) against the apps built with AddressSanitizer and
# UndefinedBehaviorSanitizer in a build tree of their own (apps only, -O0: the table's inputs are
# small, and it compiles fastest; a unity build, ROADSLAM_UNITY=OFF in the environment turns it off).
# ctest runs it as BadInputsUnderSanitizers (label `sanitize`);
# by hand: bash scripts/sanitize.sh [BUILD_DIR]   (BUILD_DIR holds the built table, default build)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=$(realpath "${1:-build}")
SAN_DIR=$(realpath -m "${SAN_DIR:-$BUILD_DIR-sanitize}")
mkdir -p "$SAN_DIR"
echo "== configuring and building the apps with -fsanitize=address,undefined in $SAN_DIR"
cmake -S . -B "$SAN_DIR" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O0 -g1" \
  -DROADSLAM_SANITIZE=ON -DROADSLAM_BUILD_TESTS=OFF -DROADSLAM_BUILD_BENCH=OFF \
  -DROADSLAM_UNITY="${ROADSLAM_UNITY:-ON}" > "$SAN_DIR/sanitize-configure.log"
if ! cmake --build "$SAN_DIR" -j"$(nproc)" --target roadslam-map roadslam-bounds roadslam-can roadslam-rawlog \
  roadslam-eval roadslam-sim roadslam-grab roadslam-experiment roadslam-report roadslam-view > "$SAN_DIR/sanitize-build.log" 2>&1; then
  tail -30 "$SAN_DIR/sanitize-build.log"
  exit 1
fi
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
echo "== the bad-input table against $SAN_DIR/bin"
ROADSLAM_BIN_DIR="$SAN_DIR/bin" "$BUILD_DIR/tests/bad_inputs"
