#pragma once
/// \file kitti_scans.h
/// KITTI Velodyne sweeps: `.bin` files of little-endian float32 records (x, y, z, reflectance),
/// 16 bytes per point, in the velodyne frame (x forward, y left, z up; metres). KITTI sweeps carry no
/// per-point time and no ring id, so the Scan flags has_point_times and has_rings are false.

#include "roadslam/common/scan.h"
#include "roadslam/common/sweep_timing.h"

#include <cmath>
#include <string>
#include <vector>

namespace roadslam {
class ParamTable;
}

namespace roadslam::datasets {

/// Reads one KITTI .bin sweep. Reflectance [0..1] is stored in ScanPoint::intensity unchanged.
/// Throws std::runtime_error naming \p path when it cannot be read or its size is not a multiple of 16.
Scan readKittiBin(const std::string& path, double stamp_s = 0.0);

/// Writes \p scan as a KITTI .bin (x, y, z, intensity as float32), atomically.
void writeKittiBin(const std::string& path, const Scan& scan);

/// What a KITTI folder leaves unsaid, as properties of the source. Ini section [kitti].
struct KittiParams {
  /// Estimate per-point times from the azimuth (KITTI stores none), so the odometry can deskew [-]
  bool times_from_azimuth = true;
  /// The sweep's timing. KITTI raw: 10 Hz, cut behind the car, stamps when the sensor faces
  /// forward (KITTI raw data readme), i.e. the middle of the sweep. Ini keys sweep_period_s, spin
  /// (clockwise | counterclockwise), cut_azimuth_deg, stamp_reference (start | middle | end).
  SweepTiming timing{0.1, SpinDirection::Clockwise, 180.0, StampReference::Middle};
  /// Added to every point's elevation, range and azimuth kept [rad]; ini elevation_correction_deg.
  /// KITTI's HDL-64E points lie about 0.22 deg too low (Deschaud, IMLS-SLAM, ICRA 2018, Sec. V-A):
  /// the road looks like a cone around the sensor, and an odometry on it drifts in pitch and height.
  double elevation_correction_rad = 0.22 * M_PI / 180.0;

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "kitti");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "kitti") const;
};

/// A folder of NNNNNN.bin sweeps in name order, with optional times.txt (one stamp [s] per line)
/// found beside the .bin files or one level up (KITTI odometry: sequences/00/{times.txt,velodyne/}).
class KittiScanFolder {
 public:
  /// Lists \p folder; throws when it does not exist, holds no .bin file, or the times file (if
  /// present) has a malformed line (file:line named) or a count different from the number of sweeps.
  /// \p times_path overrides the search for times.txt (KITTI raw keeps it elsewhere).
  explicit KittiScanFolder(const std::string& folder, const std::string& times_path = "",
                           KittiParams params = {});

  size_t size() const { return files_.size(); }
  const std::string& path(size_t i) const { return files_.at(i); }
  bool hasTimes() const { return !times_s_.empty(); }
  /// Stamp of sweep \p i [s, as in times.txt]; 0.1 s * i (KITTI's 10 Hz) when there is no times.txt.
  double stamp(size_t i) const;
  /// Reads sweep \p i (throws like readKittiBin), timed as KittiParams says: with times from the
  /// azimuth, Scan::stamp_s is the first firing (stamp(i) less the stamp reference's share).
  Scan read(size_t i) const;
  const KittiParams& params() const { return params_; }
  const std::string& timesFile() const { return times_file_; }

 private:
  std::vector<std::string> files_;
  std::vector<double> times_s_;
  std::string times_file_;
  KittiParams params_;
};

/// Unpacks \p tar_zst (a tar compressed with zstd) into \p dest_dir once: when \p dest_dir already
/// holds the completion marker of an earlier unpack it returns at once, so tests share one unpack.
/// Unpacks into a temporary sibling and renames it, so an interrupted unpack is never reused.
/// Throws naming the archive when zstd/tar fail. Returns \p dest_dir.
std::string unpackTarZstOnce(const std::string& tar_zst, const std::string& dest_dir);

}  // namespace roadslam::datasets
