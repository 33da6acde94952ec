#!/bin/bash
# The experiment runner's cost and its pool's speed-up, measured in one run: the same experiment with
# --jobs 1 and --jobs 2 (every job rerun: --force). Overhead = the runner's wall time beyond the jobs'
# own wall times (planning, hashing, process start, collecting, the report) over the jobs' time.
#   bench/experiment_overhead.sh [EXP.ini=ini/experiments/runner-overhead.ini] [BUILD=build]
set -euo pipefail
cd "$(dirname "$0")/.."
EXP=${1:-ini/experiments/runner-overhead.ini}
BIN=${2:-build}/bin/roadslam-experiment
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
"$BIN" --config "$EXP" --out "$OUT" --quiet --jobs 2 || true   # simulate the datasets once, outside the timing
row() {
  local jobs=$1 t0 t1
  t0=$(date +%s.%N)
  "$BIN" --config "$EXP" --out "$OUT" --quiet --force --jobs "$jobs" || true
  t1=$(date +%s.%N)
  /usr/bin/python3 - "$OUT/results.json" "$t0" "$t1" "$jobs" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); t0, t1, jobs = float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
own = sum(j["metrics"].get("wall_s", 0) for j in r["jobs"])
wall = t1 - t0
print(f"{jobs:>5d} {len(r['jobs']):>5d} {wall:>9.2f} {own:>12.2f} {100 * (wall * jobs - own) / own:>11.2f}")
PY
}
echo "$(basename "$EXP"): runner wall time against the jobs' own wall times (overhead = wall x jobs - own, over own)"
printf "%5s %5s %9s %12s %11s\n" jobs runs wall_s job_time_s overhead_%
row 1
row 2
