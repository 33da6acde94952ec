#!/usr/bin/env bash
# Do two builds write the same outputs, byte for byte? Runs both builds' roadslam-map and roadslam-bounds
# on the same inputs and compares every file they write, except what holds times (JSON keys and CSV
# columns ms, ms_*, *_ms, *_ms_*, wall_time_s) and the build's name (program_version); a path written
# into an output is compared with the before/after folder taken out.
# Inputs: the simulated urban loop, parking lot and highway (30 s each, simulated once by BEFORE's
# roadslam-sim), an objects-on and two GNSS-on runs (the urban loop with [objects] enabled; the highway
# with the simulator's gnss.nmea, and with its position packets' fixes), both real VLP-16 pcaps (the GPS
# one also with its fixes) and KITTI raw 0001 from ../shared/data, and the rawlogs roadslam-rawlog
# convert writes from the two captures with position packets (skipped, and said, when absent).
# usage: scripts/same_outputs.sh BEFORE_BIN AFTER_BIN [WORK_DIR]
#   e.g. scripts/same_outputs.sh /tmp/main/build/bin build/bin
# Exit 0 when every run succeeded on both sides and every compared file is identical; the failed runs
# and the differing files are listed otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
BEFORE=$(realpath "$1") AFTER=$(realpath "$2")
WORK=$(realpath -m "${3:-$(mktemp -d)}")
DATA=$(realpath -m ../shared/data)
mkdir -p "$WORK/drives"

# the highway with the simulator's GNSS receiver on ([gnss] enabled: gnss.nmea beside the capture)
printf '%s\n' "$(cat ini/sim/highway.ini)" "" "[gnss]" "enabled = true" > "$WORK/highway-gnss.ini"
for s in urban-loop parking-lot highway; do
  ini=ini/sim/$s.ini mark=velodyne.pcap
  [[ $s == highway ]] && ini=$WORK/highway-gnss.ini mark=gnss.nmea
  [[ -f "$WORK/drives/$s/$mark" ]] ||
    "$BEFORE/roadslam-sim" --config "$ini" --duration 30 --out "$WORK/drives/$s" --quiet
done
printf '%s\n' "$(cat ini/default.ini)" "" "[objects]" "enabled = true" > "$WORK/objects.ini"
printf '%s\n' "$(cat ini/kitti-hdl64.ini)" "" "[objects]" "enabled = true" > "$WORK/kitti-objects.ini"

# name | program args (INPUT and OUT filled in per side)
RUNS=(
  "map-urban|map --config ini/default.ini --input $WORK/drives/urban-loop/velodyne.pcap"
  "map-parking|map --config ini/default.ini --input $WORK/drives/parking-lot/velodyne.pcap"
  "map-highway|map --config ini/default.ini --input $WORK/drives/highway/velodyne.pcap"
  "map-urban-objects|map --config $WORK/objects.ini --input $WORK/drives/urban-loop/velodyne.pcap"
  "map-highway-gnss|map --config ini/default.ini --input $WORK/drives/highway/velodyne.pcap --gnss $WORK/drives/highway/gnss.nmea"
  "map-highway-gnss-input|map --config ini/default.ini --input $WORK/drives/highway/velodyne.pcap --gnss-from-input"
  "bounds-urban|bounds --config ini/bounds.ini --input $WORK/drives/urban-loop/velodyne.pcap --png-every 0"
)
CONVERTS=()
if [[ -d "$DATA/velodyne" ]]; then
  RUNS+=("map-vlp16-gps|map --config ini/default.ini --input $DATA/velodyne/mrpt_sample_velodyne_vlp16_gps.pcap"
         "map-vlp16-gps-input|map --config ini/default.ini --input $DATA/velodyne/mrpt_sample_velodyne_vlp16_gps.pcap --gnss-from-input"
         "map-vlp16-veloview|map --config ini/default.ini --input $DATA/velodyne/veloview_vlp-16-test-90deg-1-50-frames.pcap")
  # rawlogs written from the captures (their position packets' RMC as CObservationGPS), compared whole
  CONVERTS=("$DATA/velodyne/mrpt_sample_velodyne_vlp16_gps.pcap" "$DATA/velodyne/veloview_monterey-first-100-packets.pcap")
else
  echo "== $DATA/velodyne absent: the real VLP-16 pcaps are not compared"
fi
KITTI=$DATA/kitti/raw-2011_09_26-0001
if [[ -f "$KITTI/velodyne.tar.zst" ]]; then
  if [[ ! -d "$WORK/kitti-0001/velodyne_points" ]]; then
    mkdir -p "$WORK/kitti-0001"
    tar -C "$WORK/kitti-0001" -I zstd -xf "$KITTI/velodyne.tar.zst"
  fi
  KDIR=$(dirname "$(find "$WORK/kitti-0001" -name '*.bin' -print -quit)")
  RUNS+=("map-kitti-0001|map --config ini/kitti-hdl64.ini --input $KDIR --times $KITTI/times.txt"
         "map-kitti-0001-objects|map --config $WORK/kitti-objects.ini --input $KDIR --times $KITTI/times.txt")
else
  echo "== $KITTI absent: KITTI raw 0001 is not compared"
fi

# a run that fails on either side fails the comparison: two failed runs' folders would match
failed=0
for pcap in "${CONVERTS[@]}"; do
  name=rawlog-$(basename "$pcap" .pcap)
  for side in before after; do
    bin=$BEFORE; [[ $side == after ]] && bin=$AFTER
    mkdir -p "$WORK/$side/$name"
    "$bin/roadslam-rawlog" convert "$pcap" "$WORK/$side/$name/out.rawlog" > "$WORK/$side-$name.log" 2>&1 ||
      { echo "== FAILED: $side $name (log $WORK/$side-$name.log)"; failed=$((failed + 1)); }
    # the rawlog is gzip: compare what it holds, not the compressor's header
    [[ -f "$WORK/$side/$name/out.rawlog" ]] && gzip -dc "$WORK/$side/$name/out.rawlog" > "$WORK/$side/$name/out.rawlog.raw" &&
      rm "$WORK/$side/$name/out.rawlog"
  done
done
for run in "${RUNS[@]}"; do
  name=${run%%|*} args=${run#*|}
  prog=${args%% *} rest=${args#* }
  for side in before after; do
    bin=$BEFORE; [[ $side == after ]] && bin=$AFTER
    rm -rf "$WORK/$side/$name"
    rc=0
    # shellcheck disable=SC2086
    "$bin/roadslam-$prog" $rest --out "$WORK/$side/$name" --quiet > "$WORK/$side-$name.log" 2>&1 || rc=$?
    if ((rc)); then
      echo "== FAILED: $side $name exited $rc (log $WORK/$side-$name.log)"
      failed=$((failed + 1))
    fi
  done
done

/usr/bin/python3 - "$WORK" "$failed" <<'PY'
import json, os, re, sys, filecmp
work, failed = sys.argv[1], int(sys.argv[2])
# what differs between two runs of one binary (times) or two builds (program_version names the commit)
VOLATILE = re.compile(r"^ms$|^ms_|_ms$|_ms_|^wall_time_s$|^program_version$")
SIDES = [os.path.join(work, side) + os.sep for side in ("before", "after")]
def csv_rows(path):
    """The rows without the columns that hold times (frames.csv's ms_*)."""
    with open(path) as f:
        lines = f.read().splitlines()
    if not lines:
        return lines
    keep = [i for i, c in enumerate(lines[0].split(",")) if not VOLATILE.search(c)]
    return [[r[i] for i in keep if i < len(r)] for r in (l.split(",") for l in lines)]
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if not VOLATILE.search(k)}
    if isinstance(o, list):
        return [strip(v) for v in o]
    if isinstance(o, str):  # a path into the run's own folder (summary.json's enu_maps dir) names its side
        for side in SIDES:
            o = o.replace(side, "WORK/SIDE/")
    return o
same = differ = 0
for name in sorted(os.listdir(os.path.join(work, "before"))):
    b_dir, a_dir = os.path.join(work, "before", name), os.path.join(work, "after", name)
    for root, _, files in os.walk(b_dir):
        for f in sorted(files):
            b = os.path.join(root, f)
            a = os.path.join(a_dir, os.path.relpath(b, b_dir))
            rel = os.path.relpath(b, os.path.join(work, "before"))
            if not os.path.exists(a):
                print("missing after:", rel); differ += 1; continue
            if f.endswith(".json") or f.endswith(".jsonl"):
                ok = True
                with open(b) as fb, open(a) as fa:
                    if f.endswith(".jsonl"):
                        ok = [strip(json.loads(l)) for l in fb if l.strip()] == [strip(json.loads(l)) for l in fa if l.strip()]
                    else:
                        ok = strip(json.load(fb)) == strip(json.load(fa))
            elif f.endswith(".csv"):
                ok = csv_rows(b) == csv_rows(a)
            else:
                ok = filecmp.cmp(b, a, shallow=False)
            if ok: same += 1
            else: print("DIFFERS:", rel); differ += 1
    for root, _, files in os.walk(a_dir):
        for f in files:
            if not os.path.exists(os.path.join(b_dir, os.path.relpath(os.path.join(root, f), a_dir))):
                print("new after:", os.path.relpath(os.path.join(root, f), os.path.join(work, "after"))); differ += 1
print(f"== {same} files identical, {differ} differ, {failed} runs failed ({work})")
sys.exit(1 if differ or failed else 0)
PY
