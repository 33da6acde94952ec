#pragma once
/// \file rawlog_source.h
/// Replays an MRPT rawlog as raw packets: every CObservationVelodyneScan's scan_packets come back
/// as 1206-byte RawPackets (byte-identical to what was recorded), CObservationGPS records are
/// turned into gnss::GnssFix values. Observations are read one at a time (no full load), from both the
/// "observations" and the "sensory frames" rawlog formats.

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "roadslam/sources/gps_fix.h"
#include "roadslam/sources/packet_source.h"

namespace mrpt::obs {
class CObservationVelodyneScan;
}

namespace roadslam::sources {

/// The data packets of a recorded sweep, byte for byte, addressed to \p data_port and stamped as
/// recorded: the observation's originalReceivedTimestamp (else timestamp) for the first, plus the
/// sensor counter's advance (wrapping at the hour) for the following ones.
std::vector<velodyne::RawPacket> packetsOfScan(const mrpt::obs::CObservationVelodyneScan& v, uint16_t data_port);

class RawlogPacketSource : public PacketSource {
 public:
  /// Opens \p path; throws std::runtime_error naming the file when it is missing or unreadable.
  explicit RawlogPacketSource(const std::string& path, const PortConfig& ports = {});
  ~RawlogPacketSource() override;

  /// Data packets on ports.data_port. Stamps: the observation's originalReceivedTimestamp (or
  /// timestamp) for the first packet, plus the sensor counter's advance for the following ones.
  std::optional<velodyne::RawPacket> next() override;
  bool finished() const override { return finished_ && queue_.empty(); }
  const SourceStats& stats() const override { return stats_; }
  std::string describe() const override { return "rawlog:" + path_; }
  std::string errorMessage() const override { return error_; }
  /// Compressed bytes of the file read and its size.
  ReadProgress readProgress() const override;

  /// GPS fixes (CObservationGPS records with an RMC message) read since the last call.
  std::vector<gnss::GnssFix> takeDecodedFixes() override;
  /// CObservationVelodyneScan records read so far (= sweeps as written) [count].
  std::size_t scansRead() const { return scans_; }
  /// Records that are neither Velodyne scans nor GPS [count].
  std::size_t otherRecords() const { return other_; }
  /// A record that is neither a Velodyne scan nor GPS (e.g. the grabber's CAN observations).
  struct OtherRecord {
    std::string label;       ///< sensorLabel
    std::string class_name;  ///< e.g. "CObservationOdometry"
    double stamp_s = 0;      ///< observation timestamp [s since epoch]
  };
  /// Those records read since the last call, when keepOtherRecords(true) was set before reading.
  std::vector<OtherRecord> takeOtherRecords();
  void keepOtherRecords(bool keep) { keep_other_ = keep; }
  /// sensorLabel of the CObservationVelodyneScan whose packets next() returns now (one scan is
  /// queued at a time), e.g. to tell several LiDARs of one rawlog apart.
  const std::string& scanLabel() const { return scan_label_; }

 private:
  bool readMore();

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_, error_, scan_label_;
  PortConfig ports_;
  std::deque<velodyne::RawPacket> queue_;
  std::vector<gnss::GnssFix> gps_;
  SourceStats stats_;
  GapCounter gaps_;
  std::size_t scans_ = 0, other_ = 0;
  bool keep_other_ = false;
  std::vector<OtherRecord> others_;
  bool finished_ = false;
};

}  // namespace roadslam::sources
