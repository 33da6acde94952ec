#include "roadslam/velodyne/decoder.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roadslam::velodyne {
namespace {

constexpr double kAzimuthUnit_rad = kAzimuthUnit_deg * M_PI / 180.0;

inline uint16_t le16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }

/// Firing timing of one model: offset of channel c of block b after the packet timestamp [us].
struct Timing {
  bool vlp16;
  double block_period_us;  // time between consecutive (non-dual) blocks
  double offset_us(int block_pair, int channel) const {
    if (vlp16)  // two sequences per block (VLP-16 manual 9.5, eq. for TimeOffset)
      return block_pair * 2 * 55.296 + (channel / 16) * 55.296 + (channel % 16) * 2.304;
    return block_pair * 46.08 + channel * 1.152;  // HDL-32E manual, firing timing
  }
};

}  // namespace

int blockAzimuthStep(const std::array<uint16_t, kBlocksPerPacket>& az) {
  std::array<int, kBlocksPerPacket - 1> d{};
  for (int i = 0; i + 1 < kBlocksPerPacket; ++i) d[i] = (36000 + az[i + 1] - az[i]) % 36000;
  std::nth_element(d.begin(), d.begin() + 6, d.end());
  return d[6];
}

const char* toString(DecodeStatus status) {
  switch (status) {
    case DecodeStatus::Ok: return "ok";
    case DecodeStatus::WrongSize: return "wrong_size";
    case DecodeStatus::BadBlockFlag: return "bad_block_flag";
    case DecodeStatus::UnknownModel: return "unknown_model";
  }
  return "?";
}

double packetDuration_s(Model model) {
  return model == Model::HDL32 ? kBlocksPerPacket * kHdl32BlockPeriod_s
                               : kVlp16SequencesPerPacket * kVlp16SequencePeriod_s;
}

Decoder::Decoder(const DecoderParams& params)
    : params_(params), vlp16_(Calibration::builtinVlp16()), hdl32_(Calibration::builtinHdl32()) {
  if (!params.calibration_file.empty()) {
    Calibration c = Calibration::fromXmlFile(params.calibration_file);
    (c.model == Model::VLP16 ? vlp16_ : hdl32_) = std::move(c);
  }
}

Decoder::Decoder(const DecoderParams& params, const Calibration& calibration)
    : params_(params), vlp16_(Calibration::builtinVlp16()), hdl32_(Calibration::builtinHdl32()) {
  if (calibration.model == Model::VLP16 && calibration.size() == 16) vlp16_ = calibration;
  else if (calibration.model == Model::HDL32 && calibration.size() == 32) hdl32_ = calibration;
  else throw std::invalid_argument("Decoder: calibration must hold 16 (VLP-16) or 32 (HDL-32E) lasers");
}

const Calibration& Decoder::calibration(Model model) const {
  return model == Model::HDL32 ? hdl32_ : vlp16_;
}

Model Decoder::modelOf(const uint8_t* data, std::size_t size) const noexcept {
  if (params_.model != Model::Unknown) return params_.model;
  if (size != kDataPacketSize) return Model::Unknown;
  const uint8_t product = data[kProductIdOffset];
  if (product != static_cast<uint8_t>(Model::VLP16) && product != static_cast<uint8_t>(Model::HDL32))
    return Model::Unknown;
  if (stream_model_ != Model::Unknown) return stream_model_;
  return static_cast<Model>(product);
}

namespace {

/// Per-packet constants shared by the blocks of one packet.
struct PacketContext {
  const Calibration* cal;
  Timing timing;
  double step_per_us;  // azimuth advance [0.01 deg / us]
  bool dual, vlp16, keep_last, keep_strongest, drop_dups;
  double min_range_m, max_range_m;
};

/// Decodes block \p b (VLP-16 manual 9.3, 9.5; HDL-32E manual appendix E) into \p out.
void decodeBlock(const PacketContext& k, const uint8_t* blk, int b, uint16_t az,
                 std::vector<ScanPoint>& out) {
  const int pair = k.dual ? b / 2 : b;
  // Dual mode (VLP-16 manual 9.3.2.2): block 2j = last return, block 2j+1 = strongest.
  const bool last_block = k.dual && (b % 2) == 0;
  if (k.dual && ((last_block && !k.keep_last) || (!last_block && !k.keep_strongest))) return;
  const double t0_us = k.timing.offset_us(pair, 0);
  for (int c = 0; c < kChannelsPerBlock; ++c) {
    const uint8_t* ch = blk + 4 + 3 * c;
    const uint16_t raw = le16(ch);
    if (raw == 0) continue;  // no return
    if (last_block && k.drop_dups) {
      const uint8_t* twin = ch + kBlockSize;  // same channel, strongest block
      if (le16(twin) == raw && twin[2] == ch[2]) continue;  // VeloView keeps one of equal returns
    }
    const LaserCalibration& lc = k.cal->lasers[static_cast<std::size_t>(k.vlp16 ? c % 16 : c)];
    const double range = raw * kDistanceUnit_m + lc.distance_correction_m;
    if (range <= 0 || range < k.min_range_m || range > k.max_range_m) continue;
    const double t_us = k.timing.offset_us(pair, c);
    double a_units = az + k.step_per_us * (t_us - t0_us);
    if (a_units >= 36000.0) a_units -= 36000.0;
    const double a = a_units * kAzimuthUnit_rad - lc.azimuth_correction_rad;
    const double ca = std::cos(a), sa = std::sin(a);
    const double xy = range * lc.cos_vert - lc.vertical_offset_m * lc.sin_vert;
    ScanPoint p;  // calibration.h: our frame is VeloView's (y_vv, -x_vv, z_vv)
    p.x = static_cast<float>(xy * ca + lc.horizontal_offset_m * sa);
    p.y = static_cast<float>(-xy * sa + lc.horizontal_offset_m * ca);
    p.z = static_cast<float>(range * lc.sin_vert + lc.vertical_offset_m);
    p.intensity = ch[2];
    p.t = static_cast<float>(t_us * 1e-6);
    p.ring = lc.ring;
    p.return_index = last_block ? 1 : 0;
    out.push_back(p);
  }
}

}  // namespace

DecodeStatus Decoder::decode(const uint8_t* data, std::size_t size, std::vector<ScanPoint>& out,
                             PacketInfo* info) const noexcept {
  if (data == nullptr || size != kDataPacketSize) return DecodeStatus::WrongSize;
  const Model model = modelOf(data, size);
  if (model == Model::Unknown) return DecodeStatus::UnknownModel;
  std::array<uint16_t, kBlocksPerPacket> az{};
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    const uint8_t* blk = data + b * kBlockSize;
    if (le16(blk) != kBlockFlag) return DecodeStatus::BadBlockFlag;
    az[b] = le16(blk + 2) % 36000;
  }
  const uint8_t* tail = data + kTailOffset;
  PacketContext k;
  k.cal = &calibration(model);
  k.vlp16 = model == Model::VLP16;
  k.timing = Timing{k.vlp16, k.vlp16 ? 110.592 : 46.08};
  k.dual = tail[4] == static_cast<uint8_t>(ReturnMode::Dual);
  k.step_per_us =
      params_.intra_block_azimuth ? blockAzimuthStep(az) / k.timing.block_period_us : 0.0;
  k.keep_last = params_.dual_returns != DualReturns::Strongest;
  k.keep_strongest = params_.dual_returns != DualReturns::Last;
  k.drop_dups = params_.drop_dual_duplicates && params_.dual_returns == DualReturns::Both;
  k.min_range_m = params_.min_range_m;
  k.max_range_m = params_.max_range_m;
  PacketInfo local;
  PacketInfo& pi = info != nullptr ? *info : local;
  pi.model = model;
  pi.mode = static_cast<ReturnMode>(tail[4]);  // raw byte; only 0x39 changes decoding
  pi.timestamp_us = uint32_t{tail[0]} | (uint32_t{tail[1]} << 8) | (uint32_t{tail[2]} << 16) |
                    (uint32_t{tail[3]} << 24);
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    pi.block_azimuth[b] = az[b];
    pi.block_first_point[b] = static_cast<uint32_t>(out.size());
    pi.block_time_s[b] = static_cast<float>(k.timing.offset_us(k.dual ? b / 2 : b, 0) * 1e-6);
    decodeBlock(k, data + b * kBlockSize, b, az[b], out);
  }
  pi.end_point = static_cast<uint32_t>(out.size());
  return DecodeStatus::Ok;
}

}  // namespace roadslam::velodyne
