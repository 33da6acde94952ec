#pragma once
/// \file scan_source.h
/// One interface for every origin of decoded sweeps: Velodyne packets (live UDP, pcap, MRPT rawlog)
/// through SweepSource, and KITTI folders of NNNNNN.bin sweeps; a merged multi-sensor source later.
/// The jobs (roadslam-map, roadslam-bounds) and the odometry consume a ScanSource and never know
/// whether data is live or recorded, nor of which kind (STYLE.md rule 3). openScanSource() opens a
/// recording by what its path is.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/common/scan.h"
#include "roadslam/sources/gps_fix.h"
#include "roadslam/sources/packet_source.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam::sources {

/// The LiDAR model a source decodes its packets as, and why (velodyne/model_choice.h): summary.json's
/// lidar_model, lidar_model_source and lidar_layout (docs/run-folder.md).
struct LidarModelReport {
  std::string model;   ///< "VLP-16", "HDL-32E", "unknown" (not decoded), "undecided" (nothing read yet)
  std::string source;  ///< "ini", "packet layout" or "product byte"
  std::string layout;  ///< what the packets' layout says (velodyne::LayoutVerdict::describe)
};

/// What every scan source counts; the per-sweep path counts problems here, never throws.
struct ScanSourceStats {
  uint64_t sweeps = 0;             ///< sweeps closed (partial included) [count]
  uint64_t partial_sweeps = 0;     ///< of which the first/last partial sweeps (returned, flagged) [count]
  uint64_t packets = 0;            ///< packets read (Velodyne inputs; 0 for KITTI) [count]
  uint64_t malformed_packets = 0;  ///< packets rejected by the source or the decoder; KITTI: unreadable .bin files [count]
};

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  /// Next sweep in the lidar frame (see roadslam/common/scan.h). nullopt: end of a recording, or
  /// (live) no sweep completed within the backend's timeout; tell them apart with finished().
  virtual std::optional<Scan> next() = 0;
  /// True once a recording is exhausted and every sweep was returned.
  virtual bool finished() const = 0;
  /// GPS fixes received since the last call, in arrival order (none for sources without GPS).
  virtual std::vector<gnss::GnssFix> takeGpsFixes() { return {}; }
  /// Short human-readable origin, e.g. "pcap:/path/file.pcap" or "kitti:/path/velodyne_points/data".
  virtual std::string describe() const = 0;
  /// Counters so far (see ScanSourceStats).
  virtual ScanSourceStats stats() const = 0;
  /// Total sweeps when known in advance (KITTI folders), else 0: for progress and ETA.
  virtual size_t sizeHint() const { return 0; }
  /// Bytes of a recorded input read so far and in all (packet recordings; both 0 when unknown, live):
  /// progress and ETA where the sweeps are not counted in advance.
  virtual ReadProgress readProgress() const { return {}; }
  /// The model Velodyne packets are decoded as; nullopt for sources of points (KITTI folders).
  virtual std::optional<LidarModelReport> lidarModel() const { return std::nullopt; }
  /// Non-empty once the input turned out damaged (truncated, undecodable record, unreadable .bin):
  /// names the file and the place; the sweeps before it were returned normally.
  virtual std::string errorMessage() const { return {}; }
  /// Sweeps returned before the damage (all of them when the source stops there, as a packet
  /// source does; a KITTI folder goes on past an unreadable .bin) [count].
  virtual uint64_t sweepsBeforeDamage() const { return stats().sweeps; }
  /// What the source had to assume, for the run's summary (e.g. a KITTI folder without a times file
  /// timed at its nominal sweep period). Empty when nothing was assumed.
  virtual std::vector<std::string> warnings() const { return {}; }
};

/// The one wording of a recording damaged part way, in every program that reads up to the damage
/// (roadslam-map's and roadslam-bounds' summaries, roadslam-rawlog info, roadslam-view):
/// "input damaged, 4 sweeps read before it: WHAT", with ", and 2 after it" when the reader went on past
/// it (a KITTI folder's unreadable .bin). \p what names the file and the place.
std::string damageWarning(uint64_t sweeps_before, const std::string& what, uint64_t sweeps_after = 0);
/// damageWarning() of \p source's errorMessage(); empty when it read whole.
std::string damageWarning(const ScanSource& source);

/// Opens the recording \p path by what it is: a .pcap/.pcapng (Velodyne UDP capture), a .rawlog or
/// .gz (MRPT, CObservationVelodyneScan packets), a roadslam-grab session folder (its rawlog segments
/// read in order: segmented_source.h), or a folder of KITTI NNNNNN.bin sweeps. The decoder
/// reads the [velodyne] section of \p cfg (model, calibration, ...), a KITTI folder the [kitti]
/// section (datasets::KittiParams). \p times_path: the times file of a KITTI folder (one stamp [s]
/// per line) when it is not times.txt beside the .bin files or one level up; empty = search there.
/// Throws std::runtime_error naming the path when it is missing or of an unknown kind, or when
/// \p times_path is given for a recording that is not a KITTI folder.
std::unique_ptr<ScanSource> openScanSource(const std::string& path, const mrpt::config::CConfigFileBase& cfg,
                                           const std::string& times_path = "");

/// Loads the sections openScanSource() reads for any kind of input ([velodyne], [kitti]) from \p cfg
/// and drops them: a job that checks its ini's keys (checked_config.h) before it knows the input's
/// kind counts their keys as read, and a bad value fails there, naming the key.
void loadSourceSections(const mrpt::config::CConfigFileBase& cfg);

}  // namespace roadslam::sources
