#pragma once
/// \file layout.h
/// Tells a VLP-16 data-packet stream from an HDL-32E one by the packets' own layout, whatever their
/// product byte (byte 1205) says: some VLP-16 firmware sends the HDL-32E code 0x21 (the VeloView
/// VLP-16 sample capture does). Two physical cues, over the first kWindowPackets data packets:
///
/// - Block period (decisive). Between consecutive packets the sensor turned by the first blocks'
///   azimuth difference in the timestamps' difference: the rotation rate [0.01 deg/us]. The azimuth
///   step between the blocks of one packet divided by that rate is the time between blocks:
///   110.592 us on a VLP-16 (two 16-laser firing sequences of 55.296 us per block, VLP-16 manual
///   63-9243 section 9.5) and 46.08 us on an HDL-32E (one 32-laser firing per block, HDL-32E manual
///   63-9113 appendix E). The median over the window within kPeriodTolerance of one of them names
///   the model. Dropped packets do not matter (azimuth and time advance together); the sensor's
///   speed does not either (it cancels).
/// - Channel pairs (confirming). In a VLP-16 block, channels k and k+16 are the same laser fired
///   55.296 us apart (0.02 deg at 10 Hz), so their ranges agree closely; in an HDL-32E block they
///   are two lasers about 10 deg apart in elevation. On the real captures of ../shared/data the
///   agreement within max(5 cm, 2 %) is 87-100 % for the VLP-16s and 3-29 % for the HDL-32Es.
///
/// The rate cue decides; a channel cue that contradicts it makes the verdict inconclusive. When the
/// rate cue has too few samples (a stream of one packet, a sensor not turning), agreeing pairs alone
/// say VLP-16; disagreeing pairs alone say nothing (noise and damaged packets disagree too).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/velodyne/packet.h"

namespace roadslam::velodyne {

/// What the packets' layout says (LayoutDetector::verdict()).
struct LayoutVerdict {
  Model model = Model::Unknown;          ///< VLP16 / HDL32 by the cues; Unknown = inconclusive
  double block_period_us = std::nan(""); ///< median time between firing blocks [us]; NaN without samples
  std::size_t rate_samples = 0;          ///< consecutive packet pairs that gave a block period [count]
  double channel_agreement = std::nan("");  ///< fraction of channel pairs k / k+16 with equal ranges [-]
  std::size_t channel_pairs = 0;         ///< pairs where both channels had a return [count]
  std::size_t packets = 0;               ///< data packets examined [count]
  int product_byte = -1;                 ///< byte 1205 of the first data packet; -1 without one

  /// "VLP-16 layout (110.6 us per block)", "HDL-32E layout (channels k and k+16 agree in 3 % of
  /// 13133 pairs)", "layout inconclusive (...)", or "no data packets".
  std::string describe() const;
};

class LayoutDetector {
 public:
  static constexpr std::size_t kWindowPackets = 100;  ///< data packets examined [count]
  static constexpr double kPeriodTolerance = 0.10;    ///< relative band around a nominal block period [-]
  static constexpr std::size_t kMinRateSamples = 5;   ///< [count]
  static constexpr std::size_t kMinChannelPairs = 100;  ///< [count]
  static constexpr double kVlp16MinAgreement = 0.70;  ///< channel cue says VLP-16 at or above [-]
  static constexpr double kHdl32MaxAgreement = 0.45;  ///< channel cue says HDL-32E at or below [-]

  /// Feeds one UDP payload in arrival order; anything but a 1206-byte packet with valid block flags
  /// is ignored, and so is everything once full().
  void add(const uint8_t* data, std::size_t size);
  bool full() const { return packets_ >= kWindowPackets; }
  std::size_t packets() const { return packets_; }
  LayoutVerdict verdict() const;

 private:
  std::size_t packets_ = 0;
  int product_byte_ = -1;
  bool have_prev_ = false;
  uint16_t prev_azimuth_ = 0;  // first block of the previous packet [0.01 deg]
  uint32_t prev_stamp_us_ = 0;
  std::vector<double> periods_us_;
  std::size_t pairs_ = 0, agreeing_ = 0;
};

/// "VLP-16", "HDL-32E", "unknown": the names the summaries print.
std::string displayName(Model model);

}  // namespace roadslam::velodyne
