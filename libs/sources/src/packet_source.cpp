#include "roadslam/sources/packet_source.h"

#include <cmath>

#include "roadslam/velodyne/packet.h"

namespace roadslam::sources {
namespace {
constexpr int64_t kHour_us = 3600LL * 1000000LL;

uint32_t readLe32(const uint8_t* p) {
  return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
}  // namespace

double GapCounter::packetPeriod_s(velodyne::Model model, bool dual) {
  const double single = model == velodyne::Model::HDL32
                            ? velodyne::kBlocksPerPacket * velodyne::kHdl32BlockPeriod_s
                            : velodyne::kVlp16SequencesPerPacket * velodyne::kVlp16SequencePeriod_s;
  return dual ? 0.5 * single : single;
}

uint64_t GapCounter::feed(const uint8_t* payload) {
  const int64_t t_us = readLe32(payload + velodyne::kTimestampOffset);
  const bool dual = payload[velodyne::kReturnModeOffset] == uint8_t(velodyne::ReturnMode::Dual);
  const auto model = model_ != velodyne::Model::Unknown ? model_
                                                        : velodyne::Model(payload[velodyne::kProductIdOffset]);
  const double period_us =
      forced_period_s_ > 0 ? forced_period_s_ * 1e6 : packetPeriod_s(model, dual) * 1e6;
  uint64_t lost = 0;
  if (last_us_ >= 0) {
    int64_t step = t_us - last_us_;
    if (step < -kHour_us / 2) step += kHour_us;  // the counter wraps at the top of the hour
    if (step > 1.5 * period_us) lost = uint64_t(std::llround(step / period_us)) - 1;
  }
  last_us_ = t_us;
  missing_ += lost;
  return lost;
}

PacketKind classify(const PortConfig& ports, uint16_t dst_port, std::size_t size) {
  if (dst_port == ports.data_port)
    return size == velodyne::kDataPacketSize ? PacketKind::Data : PacketKind::Malformed;
  if (dst_port == ports.position_port)
    return size == velodyne::kPositionPacketSize ? PacketKind::Position : PacketKind::Malformed;
  return PacketKind::Other;
}

bool accountPacket(const PortConfig& ports, const velodyne::RawPacket& pkt, SourceStats& stats,
                   GapCounter& gaps) {
  switch (classify(ports, pkt.dst_port, pkt.payload.size())) {
    case PacketKind::Malformed: ++stats.malformed_packets; return false;
    case PacketKind::Other: ++stats.skipped_packets; return false;
    case PacketKind::Data:
      ++stats.data_packets;
      gaps.feed(pkt.payload.data());
      stats.missing_packets = gaps.missing();
      break;
    case PacketKind::Position: ++stats.position_packets; break;
  }
  if (stats.packets == 0) stats.first_stamp_s = pkt.stamp_s;
  stats.last_stamp_s = pkt.stamp_s;
  ++stats.packets;
  return true;
}

}  // namespace roadslam::sources
