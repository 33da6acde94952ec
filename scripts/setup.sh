#!/usr/bin/env bash
# Installs roadslam's Debian 12 dependencies, builds everything, and runs the main job on the
# bundled default input. Run as root on a fresh Debian 12 machine (apt reachable).
#   bash scripts/setup.sh            # install + build + main job
#   SKIP_APT=1 bash scripts/setup.sh # build + main job only
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(
  build-essential cmake pkg-config git
  libmrpt-dev liboctomap-dev libnanoflann-dev libeigen3-dev libpcap-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev zstd libzstd-dev zlib1g-dev
  python3-can python3-canmatrix python3-numpy can-utils tcpdump
  chromium parallel slurm-wlm munge ffmpeg
  libceres-dev          # libs/mapping: Ceres 2.1, [pose_graph] / [gnss_fusion] optimizer = ceres
  libgeographiclib-dev   # libs/gnss: WGS84, ECEF, ENU (LocalCartesian) and UTM
  libgps-dev gpsd        # libs/sources: gpsd client (roadslam-grab [gnss] source = gpsd); gpsd runs in its test
  libgl-dev xvfb xauth   # roadslam-view: OpenGL (window screenshots); its window test runs under xvfb-run
  clang libclang-rt-14-dev  # scripts/sanitize.sh: the bad-input table's apps built by clang with ASan + UBSan
)

if [[ "${SKIP_APT:-0}" != "1" ]]; then
  missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]})); then
    echo "== installing: ${missing[*]}"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends "${missing[@]}"
  fi
fi

BUILD_DIR=${BUILD_DIR:-build}
WERROR=OFF
[[ -n "${CI:-}" ]] && WERROR=ON
cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DROADSLAM_WERROR=$WERROR
cmake --build "$BUILD_DIR" -j"$(nproc)"

bash scripts/main_job.sh "$BUILD_DIR"
