#!/usr/bin/env bash
# Runs the whole test suite: ctest (unit, oracle, end-to-end, heavy, bounded fuzz) and the bad-input
# table against the apps built with ASan + UBSan (scripts/sanitize.sh, its own tree BUILD_DIR-sanitize).
# The sanitized build starts first, in the background beside ctest (both -j2: whichever ends first, the
# other has both cores); the table runs against it when it is built; the script waits for it at the end
# and fails when either ctest or the sanitized step failed (its output is printed then, and kept in
# BUILD_DIR-sanitize.log).
# With arguments, they go to ctest alone: select with ctest labels, e.g. `bash scripts/test.sh -L unit`
# or `-LE heavy`; `-L sanitize` runs the sanitized step as ctest's BadInputsUnderSanitizers.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
if (($#)); then
  exec ctest --test-dir "$BUILD_DIR" --output-on-failure -j"$(nproc)" "$@"
fi
SAN_LOG="$(realpath -m "$BUILD_DIR")-sanitize.log"
set -m  # the sanitized step in a process group of its own: stopped with the script
( SANITIZE_STEP=build bash scripts/sanitize.sh "$BUILD_DIR" &&
  SANITIZE_STEP=table bash scripts/sanitize.sh "$BUILD_DIR" ) > "$SAN_LOG" 2>&1 &
san_pid=$!
set +m
trap 'kill -- -"$san_pid" 2>/dev/null || true' INT TERM
ctest_rc=0
ctest --test-dir "$BUILD_DIR" --output-on-failure -j"$(nproc)" -LE sanitize || ctest_rc=$?
echo "== waiting for the bad-input table under sanitizers (scripts/sanitize.sh, log $SAN_LOG)"
san_rc=0
wait "$san_pid" || san_rc=$?
trap - INT TERM
if ((san_rc)); then
  cat "$SAN_LOG"
  echo "== the bad-input table under sanitizers FAILED (exit $san_rc)"
else
  tail -3 "$SAN_LOG"
fi
((ctest_rc == 0 && san_rc == 0))
