#pragma once
/// \file rawlog_writer.h
/// Writes Velodyne data as a standard MRPT rawlog ("observations" format: a gzip stream of
/// serialized CObservation objects, as CRawlog::saveToRawLogFile writes), so RawLogViewer and
/// rawlog-edit open it:
///  - one mrpt::obs::CObservationVelodyneScan per sweep, carrying the raw 1206-byte packets
///    unchanged in scan_packets (lossless: the recording format is the replay format), with
///    calibration, sensorPose (T_base_lidar), sensorLabel and minRange/maxRange;
///  - one mrpt::obs::CObservationGPS per position packet whose $GPRMC sentence parses.
/// Per-packet host stamps are not part of CObservationVelodyneScan: observation timestamp and
/// originalReceivedTimestamp hold the first packet's host stamp; later packets' stamps are
/// recovered on read from the sensor's microsecond counter (see RawlogPacketSource).
/// The file is written under a temporary name and renamed at close() (roadslam/common/atomic_file.h).

#include <memory>
#include <string>
#include <vector>

#include "roadslam/gnss/nmea.h"
#include "roadslam/velodyne/packet.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::rawlog {

class RawlogWriter {
 public:
  struct Params {
    std::string sensor_label = "VELODYNE";  ///< CObservation::sensorLabel of the scans
    std::string gps_label = "GPS";          ///< sensorLabel of the GPS observations
    std::string model = "VLP16";            ///< MRPT default calibration name (VLP16, HDL32)
    std::string calibration_file;           ///< VeloView XML; empty = MRPT default for model
    double min_range_m = 1.0;               ///< CObservationVelodyneScan::minRange [m]
    double max_range_m = 130.0;             ///< CObservationVelodyneScan::maxRange [m]
    double x_m = 0, y_m = 0, z_m = 0;       ///< T_base_lidar translation [m]
    double yaw_rad = 0, pitch_rad = 0, roll_rad = 0;  ///< T_base_lidar rotation [rad]

    /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
    void fields(ParamTable& t);
    /// Keys equal the field names, angles as yaw_deg/pitch_deg/roll_deg (converted to rad).
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
    void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
  };

  /// Opens "<path>.tmp-<pid>"; throws std::runtime_error naming \p path (or the calibration file)
  /// when it cannot be created.
  RawlogWriter(const std::string& path, const Params& params);
  ~RawlogWriter();  ///< Without close(), removes the temporary file: no half-written rawlog.
  RawlogWriter(const RawlogWriter&) = delete;
  RawlogWriter& operator=(const RawlogWriter&) = delete;

  /// One sweep of 1206-byte data packets, in order. Packets of another size are counted in
  /// skippedPackets() and not written.
  void writeSweep(const std::vector<velodyne::RawPacket>& data_packets);
  /// A 512-byte position packet; returns false (and counts it) when it holds no $GPRMC sentence.
  bool writePosition(const velodyne::RawPacket& position_packet);
  /// A GNSS receiver epoch from NMEA (fillGnssObservation), under Params::gps_label.
  void writeGnss(const gnss::GnssFix& fix);
  /// Flushes and renames onto the final path; throws naming the path on I/O error.
  void close();

  std::size_t sweepsWritten() const { return sweeps_; }
  std::size_t packetsWritten() const { return packets_; }
  std::size_t gpsWritten() const { return gps_; }
  std::size_t skippedPackets() const { return skipped_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t sweeps_ = 0, packets_ = 0, gps_ = 0, skipped_ = 0;
};

struct NmeaImportSummary {
  std::size_t epochs = 0;           ///< CObservationGPS records written (valid fixes)
  gnss::NmeaCounters counters;      ///< what the parser counted (bad checksums, no fix, ...)
  std::vector<std::string> problems;  ///< the first problems, "line N: what"
};
/// An NMEA log file (libs/gnss/nmea.h format) into a rawlog of CObservationGPS, one per valid epoch,
/// labelled \p label. Throws naming the file when it cannot be read or written; bad lines are counted.
NmeaImportSummary nmeaLogToRawlog(const std::string& nmea_path, const std::string& rawlog_path,
                                  const std::string& label = "GPS");

}  // namespace roadslam::rawlog
