#pragma once
/// \file scan_source.h
/// One interface for every origin of decoded sweeps: the Velodyne SweepSource (over live UDP,
/// pcap or rawlog packets) today, KITTI scan folders and simulators later. The odometry and
/// mapping stages consume a ScanSource and never know whether data is live or recorded
/// (STYLE.md rule 3).

#include <optional>
#include <string>
#include <vector>

#include "roadslam/common/scan.h"
#include "roadslam/sources/gps_fix.h"

namespace roadslam::sources {

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  /// Next sweep in the lidar frame (see roadslam/common/scan.h). nullopt: end of a recording, or
  /// (live) no sweep completed within the backend's timeout; tell them apart with finished().
  virtual std::optional<Scan> next() = 0;
  /// True once a recording is exhausted and every sweep was returned.
  virtual bool finished() const = 0;
  /// GPS fixes received since the last call, in arrival order (none for sources without GPS).
  virtual std::vector<TimedGpsFix> takeGpsFixes() { return {}; }
  /// Short human-readable origin, e.g. "velodyne:pcap:/path/file.pcap".
  virtual std::string describe() const = 0;
};

}  // namespace roadslam::sources
