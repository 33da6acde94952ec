#pragma once
/// \file scan_stream.h
/// Sweeps from any recorded input, by what the path is: a .pcap (Velodyne UDP capture), a .rawlog
/// (MRPT, CObservationVelodyneScan packets), or a folder of KITTI NNNNNN.bin sweeps (times.txt beside
/// or above it). The pipeline never knows which.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/common/scan.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam::pipeline {

struct StreamStats {
  size_t sweeps = 0;             ///< sweeps returned
  size_t partial_sweeps = 0;     ///< first/last partial sweeps (returned, flagged)
  size_t packets = 0;            ///< packets read (Velodyne inputs)
  size_t malformed_packets = 0;  ///< packets rejected by the decoder or the source
};

class ScanStream {
 public:
  virtual ~ScanStream() = default;
  /// The next sweep, or nullopt at the end of the input.
  virtual std::optional<Scan> next() = 0;
  virtual StreamStats stats() const = 0;
  virtual std::string describe() const = 0;
  /// Total sweeps when known in advance (KITTI folders), else 0: for progress and ETA.
  virtual size_t sizeHint() const { return 0; }
  /// Non-empty once the input turned out damaged (truncated, undecodable record, unreadable .bin):
  /// names the file and the place; the sweeps before it were returned normally.
  virtual std::string errorMessage() const { return {}; }
  /// What the stream had to assume, for the run's summary (e.g. a KITTI folder without a times file
  /// timed at its nominal sweep period). Empty when nothing was assumed.
  virtual std::vector<std::string> warnings() const { return {}; }
};

/// Opens \p path; the decoder reads the [velodyne] section of \p cfg (model, calibration, ...).
/// \p times_path: the times file of a KITTI folder (one stamp [s] per line) when it is not times.txt
/// beside the .bin files or one level up; empty = search there. Throws std::runtime_error naming the
/// path when it is missing or of an unknown kind, or when \p times_path is given for a recording
/// that is not a KITTI folder.
std::unique_ptr<ScanStream> openScanStream(const std::string& path, const mrpt::config::CConfigFileBase& cfg,
                                           const std::string& times_path = "");

}  // namespace roadslam::pipeline
