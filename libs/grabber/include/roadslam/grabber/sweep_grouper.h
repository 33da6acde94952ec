#pragma once
/// \file sweep_grouper.h
/// Groups raw data packets into one CObservationVelodyneScan per revolution without decoding:
/// a revolution ends where the block azimuth (bytes 2-3 of each 100-byte block, 0.01 deg) decreases,
/// the same cut as velodyne::SweepAssembler with cut_azimuth 0 (VeloView). A packet whose blocks
/// straddle the cut stays whole in the sweep it starts (MRPT's CVelodyneScanner keeps packets
/// whole too); replay re-cuts per block from the packets, so grouping never changes points.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "roadslam/velodyne/packet.h"

namespace roadslam::grabber {

class SweepGrouper {
 public:
  /// Adds one 1206-byte data packet. Returns true when it closed a sweep: take it with take().
  /// Packets of another size or without a valid block flag are not added (return false).
  bool add(velodyne::RawPacket&& packet);
  /// True for a 1206-byte payload whose first block carries the 0xEEFF flag (what add() takes).
  static bool accepts(const velodyne::RawPacket& packet);
  /// The closed sweep (moved out); the packets of the next sweep stay buffered.
  std::vector<velodyne::RawPacket> take();
  /// Packets of the sweep in progress (at the end of a recording: the last, partial sweep).
  std::vector<velodyne::RawPacket> takePartial();
  std::size_t pending() const { return current_.size(); }
  /// Revolutions that takePartial() cut in two: the next packet added went on with the revolution
  /// the partial sweep was in (its azimuth did not go back), so that revolution is two sweeps [count].
  std::uint64_t revolutionsCut() const { return revolutions_cut_; }

 private:
  std::vector<velodyne::RawPacket> current_, closed_;
  int prev_azimuth_ = -1;  // last block azimuth of the previous packet [0.01 deg]
  bool straddled_ = false;  // the last packet added crossed the cut inside its blocks
  int partial_azimuth_ = -1;  // after takePartial(): the last azimuth of the sweep taken, else -1
  std::uint64_t revolutions_cut_ = 0;
};

}  // namespace roadslam::grabber
