#include "roadslam/grabber/sweep_grouper.h"

namespace roadslam::grabber {
namespace {
using velodyne::kBlockSize;

int blockAzimuth(const std::uint8_t* p, int block) {
  const std::uint8_t* b = p + std::size_t(block) * kBlockSize;
  return b[2] | (b[3] << 8);
}
bool blockFlagOk(const std::uint8_t* p, int block) {
  const std::uint8_t* b = p + std::size_t(block) * kBlockSize;
  return (b[0] | (b[1] << 8)) == velodyne::kBlockFlag;
}
}  // namespace

bool SweepGrouper::accepts(const velodyne::RawPacket& packet) {
  return packet.payload.size() == velodyne::kDataPacketSize && blockFlagOk(packet.payload.data(), 0);
}

bool SweepGrouper::add(velodyne::RawPacket&& packet) {
  if (!accepts(packet)) return false;
  const std::uint8_t* p = packet.payload.data();
  if (partial_azimuth_ >= 0 && blockAzimuth(p, 0) >= partial_azimuth_) ++revolutions_cut_;
  partial_azimuth_ = -1;
  bool closes = false;
  // Cut before this packet: the previous packet ended a revolution inside its blocks, or the
  // azimuth decreased between the packets.
  if (!current_.empty() && (straddled_ || blockAzimuth(p, 0) < prev_azimuth_)) {
    closed_ = std::move(current_);
    current_.clear();
    closes = true;
  }
  straddled_ = false;
  int prev = blockAzimuth(p, 0);
  for (int b = 1; b < velodyne::kBlocksPerPacket; ++b) {
    if (!blockFlagOk(p, b)) continue;
    const int az = blockAzimuth(p, b);
    if (az < prev) straddled_ = true;
    prev = az;
  }
  prev_azimuth_ = prev;
  current_.push_back(std::move(packet));
  return closes;
}

std::vector<velodyne::RawPacket> SweepGrouper::take() { return std::move(closed_); }

std::vector<velodyne::RawPacket> SweepGrouper::takePartial() {
  std::vector<velodyne::RawPacket> out = std::move(current_);
  current_.clear();
  partial_azimuth_ = out.empty() || straddled_ ? -1 : prev_azimuth_;
  prev_azimuth_ = -1;
  straddled_ = false;
  return out;
}

}  // namespace roadslam::grabber
