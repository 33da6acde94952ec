// bench_globalreg without -DROADSLAM_BENCH_PEERS: no Open3D column.
#include "globalreg_peers.h"

namespace roadslam::bench {
bool open3dAvailable() { return false; }
std::string open3dSettings() { return "open3d: not built (cmake -DROADSLAM_BENCH_PEERS=ON, scripts/setup_peers.sh)"; }
GlobalPeerResult open3dFpfhFgr(const registration::PointCloud&, const registration::PointCloud&) { return {}; }
}  // namespace roadslam::bench
