#include "roadslam/velodyne/decoder.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roadslam::velodyne {
namespace {

constexpr double kDistanceUnit_m = 0.002;    // VLP-16 manual 9.3.1.3
constexpr double kAzimuthUnit_rad = M_PI / 18000.0;  // 0.01 deg
constexpr std::size_t kBlockSize = 100;
constexpr std::size_t kTailOffset = 1200;

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

/// Block-to-block azimuth advance [0.01 deg]: VeloView takes element 6 of the 11 sorted
/// differences, which ignores the zero steps of dual-return pairs and one wrap outlier.
int blockAzimuthStep(const uint16_t* az) {
  std::array<int, kBlocksPerPacket - 1> d{};
  for (int i = 0; i + 1 < kBlocksPerPacket; ++i) d[i] = (36000 + az[i + 1] - az[i]) % 36000;
  std::nth_element(d.begin(), d.begin() + 6, d.end());
  return d[6];
}

}  // namespace

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
  const uint8_t product = data[kTailOffset + 5];
  if (product == static_cast<uint8_t>(Model::VLP16)) return Model::VLP16;
  if (product == static_cast<uint8_t>(Model::HDL32)) return Model::HDL32;
  return Model::Unknown;
}

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
  const bool dual = data[kTailOffset + 4] == static_cast<uint8_t>(ReturnMode::Dual);
  const Calibration& cal = calibration(model);
  const Timing timing{model == Model::VLP16, model == Model::VLP16 ? 110.592 : 46.08};
  const double step_per_us =
      params_.intra_block_azimuth ? blockAzimuthStep(az.data()) / timing.block_period_us : 0.0;
  const bool keep_last = params_.dual_returns != DualReturns::Strongest;
  const bool keep_strongest = params_.dual_returns != DualReturns::Last;
  const bool drop_dups = params_.drop_dual_duplicates && params_.dual_returns == DualReturns::Both;
  PacketInfo local;
  PacketInfo& pi = info != nullptr ? *info : local;
  pi.model = model;
  pi.mode = dual ? ReturnMode::Dual : static_cast<ReturnMode>(data[kTailOffset + 4]);
  pi.timestamp_us = static_cast<uint32_t>(data[kTailOffset]) | (uint32_t{data[kTailOffset + 1]} << 8) |
                    (uint32_t{data[kTailOffset + 2]} << 16) | (uint32_t{data[kTailOffset + 3]} << 24);
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    const uint8_t* blk = data + b * kBlockSize;
    const int pair = dual ? b / 2 : b;
    // Dual mode (VLP-16 manual 9.3.2.2): block 2j = last return, block 2j+1 = strongest.
    const bool last_block = dual && (b % 2) == 0;
    const double t0_us = timing.offset_us(pair, 0);
    pi.block_azimuth[b] = az[b];
    pi.block_first_point[b] = static_cast<uint32_t>(out.size());
    pi.block_time_s[b] = static_cast<float>(t0_us * 1e-6);
    if (dual && ((last_block && !keep_last) || (!last_block && !keep_strongest))) continue;
    for (int c = 0; c < kChannelsPerBlock; ++c) {
      const uint8_t* ch = blk + 4 + 3 * c;
      const uint16_t raw = le16(ch);
      if (raw == 0) continue;
      if (last_block && drop_dups) {
        const uint8_t* twin = ch + kBlockSize;  // same channel, strongest block
        if (le16(twin) == raw && twin[2] == ch[2]) continue;  // VeloView keeps one of equal returns
      }
      const int laser = model == Model::VLP16 ? c % 16 : c;
      const LaserCalibration& lc = cal.lasers[static_cast<std::size_t>(laser)];
      const double range = raw * kDistanceUnit_m + lc.distance_correction_m;
      if (range <= 0 || range < params_.min_range_m || range > params_.max_range_m) continue;
      const double t_us = timing.offset_us(pair, c);
      double a_units = az[b] + step_per_us * (t_us - t0_us);
      if (a_units >= 36000.0) a_units -= 36000.0;
      const double a = a_units * kAzimuthUnit_rad - lc.azimuth_correction_rad;
      const double ca = std::cos(a), sa = std::sin(a);
      const double xy = range * lc.cos_vert - lc.vertical_offset_m * lc.sin_vert;
      ScanPoint p;
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
  pi.end_point = static_cast<uint32_t>(out.size());
  return DecodeStatus::Ok;
}

}  // namespace roadslam::velodyne
