#include "roadslam/velodyne/sweep_assembler.h"

#include <algorithm>
#include <cmath>

namespace roadslam::velodyne {
namespace {
constexpr int kFullTurn = 36000;  // [0.01 deg]
constexpr int64_t kHour_us = 3600LL * 1000000LL;
}  // namespace

SweepAssembler::SweepAssembler(const DecoderParams& params) : decoder_(params) {
  scratch_.reserve(kBlocksPerPacket * kChannelsPerBlock);
}

SweepAssembler::SweepAssembler(const Decoder& decoder) : decoder_(decoder) {
  scratch_.reserve(kBlocksPerPacket * kChannelsPerBlock);
}

double SweepAssembler::packetSpan_s(const PacketInfo& info) {
  float block_period = 0;
  for (int b = 1; b < kBlocksPerPacket; ++b) {
    block_period = std::max(block_period, info.block_time_s[b] - info.block_time_s[b - 1]);
  }
  return static_cast<double>(info.block_time_s[kBlocksPerPacket - 1] + block_period);
}

DecodeStatus SweepAssembler::addPacket(const uint8_t* data, std::size_t size,
                                       double capture_stamp_s) {
  ++stats_.packets;
  last_cut_block_ = -1;
  scratch_.clear();
  PacketInfo info;
  const DecodeStatus st = decoder_.decode(data, size, scratch_, &info);
  ++stats_.status[static_cast<int>(st)];
  if (st != DecodeStatus::Ok) return st;
  // Top-of-hour timestamps wrap every hour: a jump back of more than half an hour is a new hour.
  const int64_t ts = info.timestamp_us;
  if (last_ts_us_ >= 0 && ts < last_ts_us_ && last_ts_us_ - ts > kHour_us / 2)
    hour_offset_s_ += 3600.0;
  last_ts_us_ = ts;
  const double pkt_sensor_s = hour_offset_s_ + static_cast<double>(ts) * 1e-6;
  // A sensor sends a packet after its last firing, so its capture time lies one packet span
  // (VLP-16 single return: 24 x 55.296 us = 1.327 ms) after the packet's first firing.
  const double pkt_ref_s = decoder_.params().stamp_source == StampSource::Sensor
                               ? pkt_sensor_s
                               : capture_stamp_s - packetSpan_s(info);
  const int cut = static_cast<int>(
      std::lround(decoder_.params().cut_azimuth_rad * 18000.0 / M_PI) % kFullTurn);
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    const int shifted = (info.block_azimuth[b] - cut + 2 * kFullTurn) % kFullTurn;
    if (prev_shifted_az_ >= 0 && shifted < prev_shifted_az_) {
      closeSweep(first_sweep_);
      last_cut_block_ = b;
    }
    prev_shifted_az_ = shifted;
    appendBlock(info, b, pkt_sensor_s, pkt_ref_s);
  }
  return st;
}

void SweepAssembler::appendBlock(const PacketInfo& info, int b, double pkt_sensor_s,
                                 double pkt_ref_s) {
  if (!open_) {
    open_ = true;
    current_ = Scan{};
    current_.has_point_times = true;
    current_.has_rings = true;
    current_.stamp_s = pkt_ref_s + info.block_time_s[b];
    sweep_sensor_start_s_ = pkt_sensor_s + info.block_time_s[b];
  }
  const uint32_t begin = info.block_first_point[b];
  const uint32_t end = b + 1 < kBlocksPerPacket ? info.block_first_point[b + 1] : info.end_point;
  const float dt = static_cast<float>(pkt_sensor_s - sweep_sensor_start_s_);
  for (uint32_t i = begin; i < end; ++i) {
    ScanPoint p = scratch_[i];
    p.t += dt;
    current_.points.push_back(p);
  }
}

void SweepAssembler::closeSweep(bool partial) {
  if (!open_) return;
  open_ = false;
  first_sweep_ = false;
  if (current_.points.empty()) {
    ++stats_.empty_sweeps_dropped;
    return;
  }
  current_.partial = partial;
  ++stats_.sweeps;
  stats_.partial_sweeps += partial ? 1 : 0;
  stats_.points += current_.points.size();
  ready_.push_back(std::move(current_));
  current_ = Scan{};
}

void SweepAssembler::finish() { closeSweep(true); }

Scan SweepAssembler::takeSweep() {
  Scan s = std::move(ready_.front());
  ready_.pop_front();
  return s;
}

}  // namespace roadslam::velodyne
