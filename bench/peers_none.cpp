// Stand-ins when the peers are off (-DROADSLAM_BENCH_PEERS=OFF, the default): PCL and Open3D are
// optional, CI does not install them.
#include "peers.h"

namespace roadslam::bench {
void addPcl(PeerList&) {}
void addOpen3d(PeerList&) {}
}  // namespace roadslam::bench
