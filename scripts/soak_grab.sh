#!/usr/bin/env bash
# Soak test of roadslam-grab (not part of the default test run): roadslam-sim streams real-format
# VLP-16 packets to loopback for DURATION seconds at SPEED x real time while roadslam-grab records
# them with both sidecars; the grabber's resident memory is sampled every 10 s.
# Pass: no packet lost (received = sent by the simulator, packets_dropped = 0, every packet in the
# rawlog) and memory flat (RSS growth after the first minute < MAX_GROWTH_MB).
#
#   scripts/soak_grab.sh                      # 10 minutes at 1x, build/ binaries
#   BUILD=build-grab DURATION=60 SPEED=2 scripts/soak_grab.sh
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
DURATION=${DURATION:-600}   # [s] of simulated drive
SPEED=${SPEED:-1}           # pace, multiple of real time
PORT=${PORT:-23900}         # data port; position port = PORT + 1
MAX_GROWTH_MB=${MAX_GROWTH_MB:-20}
OUT=${OUT:-/tmp/soak_grab_$$}
GRAB=${GRAB:-$BUILD/bin/roadslam-grab}
SIM=${SIM:-$BUILD/bin/roadslam-sim}
for exe in "$GRAB" "$SIM"; do [[ -x $exe ]] || { echo "missing $exe (BUILD=$BUILD)" >&2; exit 2; }; done
mkdir -p "$OUT"
cat > "$OUT/soak.ini" <<INI
[grab]
sensors = lidar
flush_period_ms = 500
rotate_period_s = 120
[lidar]
model = vlp16
bind_address = 127.0.0.1
data_port = $PORT
position_port = $((PORT + 1))
INI

"$GRAB" --config "$OUT/soak.ini" --out "$OUT/session" > "$OUT/grab.out" 2> "$OUT/grab.log" &
GRAB_PID=$!
trap 'kill -INT $GRAB_PID 2>/dev/null || true' EXIT
sleep 1
"$SIM" --config ini/sim/urban-loop.ini --out "$OUT/sim" --duration "$DURATION" \
  --udp "127.0.0.1:$PORT" --speed "$SPEED" > "$OUT/sim.log" &
SIM_PID=$!
echo "t_s,rss_kb" > "$OUT/rss.csv"
T0=$(date +%s)
while kill -0 $SIM_PID 2>/dev/null; do
  echo "$(( $(date +%s) - T0 )),$(awk '/VmRSS/ {print $2}' /proc/$GRAB_PID/status)" >> "$OUT/rss.csv"
  sleep 10
done
wait $SIM_PID
sleep 1
kill -INT $GRAB_PID
wait $GRAB_PID
trap - EXIT
cat "$OUT/sim.log"
tail -n 2 "$OUT/grab.out"

/usr/bin/python3 - "$OUT" "$MAX_GROWTH_MB" <<'PY'
import csv, json, sys
out, max_growth = sys.argv[1], float(sys.argv[2])
g = json.load(open(f"{out}/session/summary.json"))
s = json.load(open(f"{out}/sim/summary.json"))
rss = [(int(r["t_s"]), int(r["rss_kb"])) for r in csv.DictReader(open(f"{out}/rss.csv")) if r["rss_kb"]]
warm = [kb for t, kb in rss if t >= 60] or [kb for _, kb in rss]
growth_mb = (max(warm) - warm[0]) / 1024
sent = s["packets_sent"]
print(f"sent {sent}, received {g['packets_received']}, written {g['packets_written']}, "
      f"dropped {g['packets_dropped']}, segments {g['rawlog_segments']}, "
      f"RSS {rss[0][1]/1024:.1f} -> {rss[-1][1]/1024:.1f} MB (growth after 60 s: {growth_mb:.1f} MB)")
ok = g["packets_received"] == sent and g["packets_written"] == sent and g["packets_dropped"] == 0 \
     and growth_mb < max_growth
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
PY
