#!/usr/bin/env bash
# GNSS figures, printed as tables: the simulated 3 km highway with a 10 Hz receiver at 1 m
# white noise (as simulated, a 30 s outage, a 50 m multipath jump) fused into roadslam-map's trajectory,
# and the real RAV4 drive (its reference at 1 Hz + 1/2/3 m noise, fused with its CAN dead reckoning).
#   bash scripts/bench_gnss.sh [BUILD_DIR]      (needs roadslam-sim, roadslam-map, bench_gnss built)
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
OUT=$B/gnss_fig
mkdir -p "$OUT"
# the highway scenario with the receiver on (10 Hz, 1 m horizontal noise)
{ cat ini/sim/highway.ini; printf '\n[gnss]\nenabled = true\nrate_hz = 10\nnoise_sigma_m = 1.0\nnoise_sigma_up_m = 1.5\n'; } > "$OUT/highway.ini"
# the antenna in the lidar frame: [gnss] lever (0.5, 0, 1.7) in the vehicle frame less the lidar mount (1.2, 0, 1.9)
sed -e '/^\[gnss_fusion\]/,$ s/^lever_x_m = 0.0/lever_x_m = -0.7/' -e '/^\[gnss_fusion\]/,$ s/^lever_z_m = 0.0/lever_z_m = -0.2/' \
  ini/default.ini > "$OUT/map-gnss.ini"
[[ -f $OUT/highway/.done ]] || { "$B/bin/roadslam-sim" --config "$OUT/highway.ini" --out "$OUT/highway" && touch "$OUT/highway/.done"; }
[[ -f $OUT/highway_map/.done ]] || { "$B/bin/roadslam-map" --config "$OUT/map-gnss.ini" --input "$OUT/highway/velodyne.pcap" \
  --gnss "$OUT/highway/gnss.nmea" --out "$OUT/highway_map" --quiet && touch "$OUT/highway_map/.done"; }
"$B/bench/bench_gnss" sim --scenario "$OUT/highway.ini" --sim "$OUT/highway" --run "$OUT/highway_map" --config "$OUT/map-gnss.ini"
echo
DATA=${ROADSLAM_SHARED_DATA:-../shared/data}
if [[ -d $DATA/can/rav4-2017 ]]; then
  "$B/bench/bench_gnss" rav4 --data "$DATA/can/rav4-2017" --vehicle ini/vehicles/toyota-rav4-2017.ini --seed 23
else
  echo "RAV4 drive skipped: $DATA/can/rav4-2017 not found"
fi
