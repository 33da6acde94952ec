#include "roadslam/velodyne/layout.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>

namespace roadslam::velodyne {
namespace {  // names unlike the other files': the unity build joins their anonymous namespaces

constexpr int kTurnUnits = 36000;                 // [0.01 deg]
constexpr int64_t kHourMicros = 3600LL * 1000000LL;
constexpr double kMaxPacketGap_us = 20000;       // beyond it the azimuth may have turned past 360 deg
constexpr double kVlp16Block_us = 2 * kVlp16SequencePeriod_s * 1e6;  // 110.592 (manual 9.5)
constexpr double kHdl32Block_us = kHdl32BlockPeriod_s * 1e6;         // 46.08 (HDL-32E appendix E)
constexpr double kPairTolerance_m = 0.05, kPairTolerance_rel = 0.02;  // equal ranges of a channel pair

inline uint16_t readU16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
inline uint32_t readU32(const uint8_t* p) {
  return uint32_t{p[0]} | (uint32_t{p[1]} << 8) | (uint32_t{p[2]} << 16) | (uint32_t{p[3]} << 24);
}

/// Mean azimuth advance between the blocks of one packet [0.01 deg]: the packet's span over its
/// non-zero steps (dual return repeats each azimuth in a block pair). A single step is quantised to
/// 0.01 deg, 2.5 % of an HDL-32E's 0.17 deg at 10 Hz; the span over 11 steps to a tenth of that.
double meanBlockStep(const std::array<uint16_t, kBlocksPerPacket>& az) {
  int span = 0, steps = 0;
  for (int i = 0; i + 1 < kBlocksPerPacket; ++i) {
    const int d = (az[i + 1] - az[i] + kTurnUnits) % kTurnUnits;  // a wrap inside the packet too
    span += d;
    steps += d > 0;
  }
  return steps > 0 ? static_cast<double>(span) / steps : 0.0;
}

Model modelOfPeriod(double period_us) {
  if (std::abs(period_us / kVlp16Block_us - 1) <= LayoutDetector::kPeriodTolerance) return Model::VLP16;
  if (std::abs(period_us / kHdl32Block_us - 1) <= LayoutDetector::kPeriodTolerance) return Model::HDL32;
  return Model::Unknown;
}

Model modelOfAgreement(double agreement) {
  if (agreement >= LayoutDetector::kVlp16MinAgreement) return Model::VLP16;
  if (agreement <= LayoutDetector::kHdl32MaxAgreement) return Model::HDL32;
  return Model::Unknown;
}

}  // namespace

std::string displayName(Model model) {
  switch (model) {
    case Model::VLP16: return "VLP-16";
    case Model::HDL32: return "HDL-32E";
    default: return "unknown";
  }
}

void LayoutDetector::add(const uint8_t* data, std::size_t size) {
  if (full() || data == nullptr || size != kDataPacketSize) return;
  std::array<uint16_t, kBlocksPerPacket> az{};
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    const uint8_t* blk = data + b * kBlockSize;
    if (readU16(blk) != kBlockFlag) return;
    az[b] = readU16(blk + 2) % kTurnUnits;
  }
  if (packets_++ == 0) product_byte_ = data[kProductIdOffset];
  const uint32_t stamp_us = readU32(data + kTimestampOffset);
  if (have_prev_) {
    int64_t dt_us = int64_t{stamp_us} - int64_t{prev_stamp_us_};
    if (dt_us < -kHourMicros / 2) dt_us += kHourMicros;  // the counter wraps at the top of the hour
    const int turned = (az[0] - prev_azimuth_ + kTurnUnits) % kTurnUnits;
    const double step = meanBlockStep(az);
    if (dt_us > 0 && dt_us < kMaxPacketGap_us && turned > 0 && step > 0)
      periods_us_.push_back(step * static_cast<double>(dt_us) / turned);  // step / (turned / dt)
  }
  have_prev_ = true;
  prev_azimuth_ = az[0];
  prev_stamp_us_ = stamp_us;
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    const uint8_t* ch = data + b * kBlockSize + 4;
    for (int k = 0; k < kChannelsPerBlock / 2; ++k) {
      const uint16_t r1 = readU16(ch + 3 * k), r2 = readU16(ch + 3 * (k + kChannelsPerBlock / 2));
      if (r1 == 0 || r2 == 0) continue;  // no return in one of them
      ++pairs_;
      const double d1 = r1 * kDistanceUnit_m, d2 = r2 * kDistanceUnit_m;
      if (std::abs(d1 - d2) <= std::max(kPairTolerance_m, kPairTolerance_rel * d1)) ++agreeing_;
    }
  }
}

LayoutVerdict LayoutDetector::verdict() const {
  LayoutVerdict v;
  v.packets = packets_;
  v.product_byte = product_byte_;
  v.rate_samples = periods_us_.size();
  v.channel_pairs = pairs_;
  Model by_rate = Model::Unknown, by_channels = Model::Unknown;
  if (!periods_us_.empty()) {
    // The mean of the samples within 10 % of their median: robust to a packet pair whose clock or
    // azimuth jumped, and averaging the 0.01 deg quantisation of the rest.
    std::vector<double> p = periods_us_;
    std::nth_element(p.begin(), p.begin() + p.size() / 2, p.end());
    const double median = p[p.size() / 2];
    double sum = 0;
    std::size_t n = 0;
    for (const double x : periods_us_)
      if (std::abs(x / median - 1) <= 0.1) sum += x, ++n;
    v.block_period_us = sum / static_cast<double>(n);  // n >= 1: the median itself
    if (p.size() >= kMinRateSamples) by_rate = modelOfPeriod(v.block_period_us);
  }
  if (pairs_ > 0) {
    v.channel_agreement = static_cast<double>(agreeing_) / static_cast<double>(pairs_);
    if (pairs_ >= kMinChannelPairs) by_channels = modelOfAgreement(v.channel_agreement);
  }
  if (by_rate != Model::Unknown)
    v.model = by_channels == Model::Unknown || by_channels == by_rate ? by_rate : Model::Unknown;
  else if (v.rate_samples < kMinRateSamples && by_channels == Model::VLP16)
    v.model = Model::VLP16;  // too few packet pairs to time a block: pairs that agree are a VLP-16's
  // (pairs that disagree alone prove nothing: noise and damaged packets disagree too)
  return v;
}

std::string LayoutVerdict::describe() const {
  if (packets == 0) return "no data packets";
  char period[64] = "", pairs[96] = "";
  if (rate_samples > 0) std::snprintf(period, sizeof period, "%.1f us per block", block_period_us);
  if (channel_pairs > 0)
    std::snprintf(pairs, sizeof pairs, "channels k and k+16 agree in %.0f %% of %zu pairs", 100 * channel_agreement,
                  channel_pairs);
  const std::string both = std::string(period) + (*period && *pairs ? ", " : "") + pairs;
  if (model == Model::Unknown)
    return "layout inconclusive (" + (both.empty() ? std::to_string(packets) + " packets" : both) + ")";
  // The cue that decided: the block period whenever it had enough samples.
  const bool by_rate = rate_samples >= LayoutDetector::kMinRateSamples;
  return displayName(model) + " layout (" + (by_rate ? std::string(period) : std::string(pairs)) + ")";
}

}  // namespace roadslam::velodyne
