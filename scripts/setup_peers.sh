#!/bin/sh
# Optional peers of bench/bench_peers (PCL, Open3D from Debian 12). Not needed to build or test
# roadslam; CI does not run this. Then: cmake -DROADSLAM_BENCH_PEERS=ON ...
set -eu
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO=sudo
$SUDO apt-get update
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends libpcl-dev libopen3d-dev
