#!/usr/bin/env bash
# The main job on the bundled default inputs:
#  1. decode the bundled box-room capture (rawlogs/boxroom-vlp16.pcap, made by our own encoder)
#     into an MRPT rawlog and print its summary;
#  2. simulate 40 s of the urban loop (deterministic for its seed; a pcap of that length would be
#     38 MB, too large to bundle), map it with ini/default.ini, and score the trajectory against the
#     simulator's exact ground truth.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${1:-build}
BIN="$BUILD_DIR/bin"
OUT=${OUT:-out/main}
mkdir -p "$OUT"

echo "== 1. decode the bundled VLP-16 capture into a rawlog"
"$BIN/roadslam-rawlog" convert rawlogs/boxroom-vlp16.pcap "$OUT/boxroom-vlp16.rawlog"
"$BIN/roadslam-rawlog" info "$OUT/boxroom-vlp16.rawlog"

echo "== 2. simulate 40 s of the urban loop, map it, score it against ground truth"
"$BIN/roadslam-sim" --config ini/sim/urban-loop.ini --duration 40 --out "$OUT/sim-urban"
"$BIN/roadslam-map" --config ini/default.ini --input "$OUT/sim-urban/velodyne.pcap" \
  --out "$OUT/map-urban" --quiet
"$BIN/roadslam-eval" --gt "$OUT/sim-urban/gt_trajectory.tum" --est "$OUT/map-urban/trajectory.tum" \
  --plot "$OUT/map-urban/eval.png"
echo "== outputs in $OUT (map: $OUT/map-urban, plot: $OUT/map-urban/eval.png)"
