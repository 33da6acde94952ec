#include "roadslam/velodyne/position.h"

#include "roadslam/velodyne/packet.h"

namespace roadslam::velodyne {

bool decodePositionPacket(const uint8_t* data, std::size_t size, PositionPacket& out) noexcept {
  if (data == nullptr || size != kPositionPacketSize) return false;
  const uint8_t* ts = data + kPositionTimestampOffset;
  out.timestamp_us = uint32_t{ts[0]} | (uint32_t{ts[1]} << 8) | (uint32_t{ts[2]} << 16) |
                     (uint32_t{ts[3]} << 24);
  try {
    out.nmea.clear();
    for (std::size_t i = kPositionNmeaOffset; i < size; ++i) {
      const char c = static_cast<char>(data[i]);
      if (c == '\0' || c == '\r' || c == '\n') break;
      out.nmea.push_back(c);
    }
  } catch (...) {
    return false;
  }
  out.fix = gnss::parseRmc(out.nmea);
  if (out.fix) out.fix->t_receive_s = gnss::kNaN;
  return true;
}

}  // namespace roadslam::velodyne
