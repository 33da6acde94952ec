#!/bin/bash
# Speed of two builds of the programs on one recording, in the same run: roadslam-map (odometry ms per
# frame, mapping total, wall), roadslam-map with [objects] enabled (the objects stage's total) and
# roadslam-bounds live with the odometry (detector ms per frame, wall),
# each build run in turn ROUNDS times so machine load hits both alike; prints medians and after/before.
# usage: scripts/compare_builds.sh BEFORE_BIN AFTER_BIN RECORDING [ROUNDS=5]
#   e.g. scripts/compare_builds.sh /tmp/old/build/bin build/bin out/main/sim-urban/velodyne.pcap
set -euo pipefail
cd "$(dirname "$0")/.."
BEFORE=$1 AFTER=$2 REC=$3 ROUNDS=${4:-5}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
printf '%s\n' "$(cat ini/default.ini)" "" "[objects]" "enabled = true" > "$TMP/objects.ini"
for r in $(seq "$ROUNDS"); do
  for side in before after; do
    bin=$BEFORE; [ "$side" = after ] && bin=$AFTER
    "$bin/roadslam-map" --config ini/default.ini --input "$REC" --out "$TMP/$side-map-$r" --quiet
    "$bin/roadslam-map" --config "$TMP/objects.ini" --input "$REC" --out "$TMP/$side-objects-$r" --quiet
    "$bin/roadslam-bounds" --config ini/bounds.ini --input "$REC" --out "$TMP/$side-bounds-$r" --quiet --png-every 0
  done
done
/usr/bin/python3 - "$TMP" "$ROUNDS" <<'PY'
import json, statistics, sys
tmp, rounds = sys.argv[1], int(sys.argv[2])
def value(summary, key):  # "a.b" reads summary["a"]["b"]
    for k in key.split("."):
        summary = summary[k]
    return summary
def med(side, job, key):
    return statistics.median(value(json.load(open(f"{tmp}/{side}-{job}-{r}/summary.json")), key) for r in range(1, rounds + 1))
rows = [("map: odometry ms/frame (mean)", "map", "ms_per_frame_mean"),
        ("map: odometry ms/frame (p95)", "map", "ms_per_frame_p95"),
        ("map: mapping ms total", "map", "ms_mapping_total"),
        ("map: wall s", "map", "wall_time_s"),
        ("map+objects: objects ms total", "objects", "ms_by_stage_total.objects"),
        ("bounds: detector ms/frame (mean)", "bounds", "ms_per_frame_mean")]
print(f"{'median of ' + str(rounds) + ' rounds':34s} {'before':>10s} {'after':>10s} {'after/before':>12s}")
for name, job, key in rows:
    b, a = med("before", job, key), med("after", job, key)
    print(f"{name:34s} {b:10.3f} {a:10.3f} {a / b:12.3f}")
PY
