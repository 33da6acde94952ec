#!/usr/bin/env bash
# The bad-input table (tests/bad_inputs.cpp) against the apps built with AddressSanitizer and
# UndefinedBehaviorSanitizer in a build tree of their own: the 10 apps the table runs (every one has
# rows) and the libraries they link, no tests or benchmarks; -O0 -g1 (the table's inputs are small, and
# it compiles fastest); clang (SAN_CXX / SAN_CC to change it): at -O0 with both sanitizers it compiles
# a unity batch in 0.57 of GCC's CPU time (docs/benchmarks.md, "Build time"); a unity build of one
# batch per target (fewest translation units: the shared headers compiled once per target;
# ROADSLAM_UNITY=OFF in the environment compiles every file alone).
# scripts/test.sh runs it beside ctest (from the start); ctest by hand runs it as
# BadInputsUnderSanitizers (label `sanitize`); by hand:
#   bash scripts/sanitize.sh [BUILD_DIR]   (BUILD_DIR holds the built table, default build)
# SANITIZE_STEP=build only configures and builds the tree, SANITIZE_STEP=table only runs the table
# against it (default: both).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=$(realpath "${1:-build}")
SAN_DIR=$(realpath -m "${SAN_DIR:-$BUILD_DIR-sanitize}")
STEP=${SANITIZE_STEP:-all}
APPS=(roadslam-map roadslam-bounds roadslam-can roadslam-rawlog roadslam-eval roadslam-sim roadslam-grab
  roadslam-experiment roadslam-report roadslam-view)
if [[ "$STEP" == all || "$STEP" == build ]]; then
  mkdir -p "$SAN_DIR"
  echo "== configuring and building the apps with -fsanitize=address,undefined in $SAN_DIR"
  cmake -S . -B "$SAN_DIR" -DCMAKE_CXX_COMPILER="${SAN_CXX:-clang++}" -DCMAKE_C_COMPILER="${SAN_CC:-clang}" \
    -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O0 -g1" \
    -DROADSLAM_SANITIZE=ON -DROADSLAM_BUILD_TESTS=OFF -DROADSLAM_BUILD_BENCH=OFF \
    -DROADSLAM_UNITY="${ROADSLAM_UNITY:-ON}" -DROADSLAM_UNITY_BATCH=0 > "$SAN_DIR/sanitize-configure.log"
  if ! cmake --build "$SAN_DIR" -j"$(nproc)" --target "${APPS[@]}" > "$SAN_DIR/sanitize-build.log" 2>&1; then
    tail -30 "$SAN_DIR/sanitize-build.log"
    exit 1
  fi
fi
if [[ "$STEP" == all || "$STEP" == table ]]; then
  export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
  export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
  echo "== the bad-input table against $SAN_DIR/bin"
  ROADSLAM_BIN_DIR="$SAN_DIR/bin" "$BUILD_DIR/tests/bad_inputs"
fi
