#pragma once
/// \file sweep_assembler.h
/// Cuts the stream of decoded data packets into sweeps (one revolution each) as roadslam::Scan.
///
/// A sweep ends where the raw block azimuth crosses DecoderParams::cut_azimuth (with the default
/// 0 deg: where the azimuth decreases), decided per block as VeloView does, so every point of a
/// block stays in the same sweep. The first sweep of a stream and the one closed by finish() are
/// flagged partial; sweeps without any point are dropped (VeloView's IgnoreEmptyFrames).
///
/// Times: Scan::stamp_s is the first firing of the sweep on the clock chosen by
/// DecoderParams::stamp_source (capture time of the packet less the packet's span, since the sensor
/// sends a packet after its last firing; or the sensor's microseconds past the top of the hour,
/// unwrapped across hours); ScanPoint::t is relative to it, from the sensor's
/// own timestamps and firing timing (no capture jitter).

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "roadslam/common/scan.h"
#include "roadslam/velodyne/decoder.h"

namespace roadslam::velodyne {

struct SweepStats {
  std::size_t packets = 0;                     ///< packets offered
  std::size_t status[kDecodeStatusCount] = {};  ///< packets per DecodeStatus
  std::size_t sweeps = 0;                      ///< sweeps emitted (partial included)
  std::size_t partial_sweeps = 0;
  std::size_t empty_sweeps_dropped = 0;
  std::size_t points = 0;                      ///< points in emitted sweeps
  std::size_t malformed() const { return packets - status[0]; }
};

class SweepAssembler {
 public:
  /// Throws like Decoder(params) on a bad calibration file.
  explicit SweepAssembler(const DecoderParams& params = {});
  explicit SweepAssembler(const Decoder& decoder);

  /// Feeds one UDP payload received at \p capture_stamp_s [s]; a bad packet is counted and skipped.
  DecodeStatus addPacket(const uint8_t* data, std::size_t size, double capture_stamp_s);
  DecodeStatus addPacket(const RawPacket& packet) {
    return addPacket(packet.payload.data(), packet.payload.size(), packet.stamp_s);
  }
  /// Block (0..11) of the last packet at which a sweep was cut, -1 if none: a packet with a cut
  /// at block k > 0 straddles two sweeps (blocks < k in the closed one). For converters that
  /// store raw packets per sweep (e.g. CObservationVelodyneScan).
  int lastCutBlock() const { return last_cut_block_; }
  /// End of stream: emits the sweep in progress (flagged partial).
  void finish();

  bool hasSweep() const { return !ready_.empty(); }
  /// Oldest completed sweep; precondition hasSweep().
  Scan takeSweep();
  const SweepStats& stats() const { return stats_; }
  const Decoder& decoder() const { return decoder_; }
  /// Decoder::setStreamModel, for the packets added from now on.
  void setStreamModel(Model model) { decoder_.setStreamModel(model); }

 private:
  /// Time from the first firing of a packet to the end of its last firing [s].
  static double packetSpan_s(const PacketInfo& info);
  void closeSweep(bool partial);
  void appendBlock(const PacketInfo& info, int block, double pkt_sensor_s, double pkt_ref_s);

  Decoder decoder_;
  std::vector<ScanPoint> scratch_;
  std::deque<Scan> ready_;
  Scan current_;
  bool open_ = false;            // current_ has started (first block seen)
  bool first_sweep_ = true;      // the next sweep closed is the stream's first
  int prev_shifted_az_ = -1;     // previous block azimuth relative to the cut [0.01 deg]
  int last_cut_block_ = -1;
  double sweep_sensor_start_s_ = 0;
  int64_t last_ts_us_ = -1;      // for top-of-hour unwrapping
  double hour_offset_s_ = 0;
  SweepStats stats_;
};

}  // namespace roadslam::velodyne
