#include "roadslam/sources/packet_source.h"

#include <cmath>

#include "roadslam/velodyne/model_choice.h"
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

velodyne::Model GapCounter::streamModel() const {
  return velodyne::chooseModel(velodyne::Model::Unknown, layout_.verdict()).model;
}

uint64_t GapCounter::lost(const Step& s, velodyne::Model model) const {
  if (model == velodyne::Model::Unknown) model = velodyne::Model(s.product);  // as the byte says
  const double period_us = forced_period_s_ > 0 ? forced_period_s_ * 1e6 : packetPeriod_s(model, s.dual) * 1e6;
  return s.step_us > 1.5 * period_us ? uint64_t(std::llround(s.step_us / period_us)) - 1 : 0;
}

uint64_t GapCounter::feed(const uint8_t* payload) {
  const int64_t t_us = readLe32(payload + velodyne::kTimestampOffset);
  const bool dual = payload[velodyne::kReturnModeOffset] == uint8_t(velodyne::ReturnMode::Dual);
  const bool by_layout = model_ == velodyne::Model::Unknown && forced_period_s_ <= 0;
  if (by_layout && !chosen_) layout_.add(payload, velodyne::kDataPacketSize);
  uint64_t n = 0;
  if (last_us_ >= 0) {
    int64_t step = t_us - last_us_;
    if (step < -kHour_us / 2) step += kHour_us;  // the counter wraps at the top of the hour
    const Step s{step, dual, payload[velodyne::kProductIdOffset]};
    if (!by_layout) n = lost(s, model_);
    else if (chosen_) n = lost(s, chosen_model_);
    else pending_.push_back(s);
  }
  last_us_ = t_us;
  if (by_layout && !chosen_ && layout_.full()) {  // the window is complete: count its steps
    chosen_ = true;
    chosen_model_ = streamModel();
    for (const auto& p : pending_) missing_ += lost(p, chosen_model_);
    pending_.clear();
  }
  missing_ += n;
  return n;
}

uint64_t GapCounter::missing() const {
  if (pending_.empty()) return missing_;
  const velodyne::Model m = streamModel();
  uint64_t n = missing_;
  for (const auto& p : pending_) n += lost(p, m);
  return n;
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
