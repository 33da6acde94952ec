#include "roadslam/sources/gps_fix.h"

namespace roadslam::sources {

std::optional<TimedGpsFix> decodeGpsFix(const velodyne::RawPacket& pkt) {
  velodyne::PositionPacket pos;
  if (!velodyne::decodePositionPacket(pkt.payload.data(), pkt.payload.size(), pos) || !pos.has_fix)
    return std::nullopt;
  return TimedGpsFix{pkt.stamp_s, pos.fix};
}

}  // namespace roadslam::sources
