#pragma once
/// \file scan_context.h
/// Place recognition by Scan Context (Kim & Kim, "Scan Context: egocentric spatial descriptor for place
/// recognition within 3D point cloud map", IROS 2018): a sweep as a polar grid of num_rings x num_sectors
/// bins around the sensor, each bin the highest point's height above the sensor plus height_offset_m;
/// the ring key (mean of each ring, rotation invariant) indexes the keyframes in a kd-tree (nanoflann),
/// and the candidates it returns are compared by the column-shifted cosine distance (eq. 5-6), which also
/// gives the yaw between the two sweeps. Nothing here knows the odometry: candidates are independent of
/// drift. Frames: points in the sweep's lidar frame [m], z up.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}
namespace roadslam {
class ParamTable;
}

namespace roadslam::place {

/// Ini section [place_recognition].
struct ScanContextParams {
  int num_rings = 20;                ///< radial bins [-]
  int num_sectors = 60;              ///< azimuth bins [-]
  double max_radius_m = 60.0;        ///< points farther are ignored [m]
  double height_offset_m = 2.0;      ///< added to z so the road (about -1.9 m for a car's lidar) is >= 0 [m]
  int ring_key_candidates = 10;      ///< nearest ring keys compared in full [-]
  double max_distance = 0.2;         ///< Scan Context distance (eq. 6) of a match below [-]
  double min_travel_m = 60.0;        ///< candidates at least this far back along the path [m]

  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "place_recognition");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "place_recognition") const;
};

/// One sweep's descriptor: num_rings x num_sectors heights [m] (0: empty bin).
struct ScanContext {
  Eigen::MatrixXf bins;      ///< rows: rings (inner to outer), columns: sectors (azimuth from -pi)
  Eigen::VectorXf ring_key;  ///< mean of each row [m]
};

/// Scan Context of \p points_lidar [m] (non-finite points skipped).
ScanContext makeScanContext(const std::vector<Eigen::Vector3d>& points_lidar, const ScanContextParams& p);

/// Distance in [0, 1] between two descriptors at the best column shift (Kim & Kim 2018 eq. 6): 1 - the
/// mean cosine similarity of the columns non-empty in both; \p shift receives the best shift [sectors],
/// the yaw of b relative to a is shift * 2 pi / num_sectors.
double scanContextDistance(const ScanContext& a, const ScanContext& b, int* shift = nullptr);

/// A match for a query: the keyframe, its distance and the yaw between them.
struct PlaceMatch {
  size_t id = 0;              ///< id given to ScanContextDatabase::add [-]
  double distance = 1;        ///< Scan Context distance [-]
  double yaw_rad = 0;         ///< yaw of the query relative to the match [rad]
};

/// Descriptors of keyframes with their path length, searchable by ring key.
class ScanContextDatabase {
 public:
  explicit ScanContextDatabase(ScanContextParams p = {});
  ~ScanContextDatabase();
  ScanContextDatabase(ScanContextDatabase&&) noexcept;
  ScanContextDatabase& operator=(ScanContextDatabase&&) noexcept;

  /// Adds keyframe \p id with \p path_m driven up to it [m]; returns its index.
  size_t add(size_t id, double path_m, ScanContext sc);
  size_t size() const;
  const ScanContext& descriptor(size_t index) const;
  size_t idAt(size_t index) const;
  /// The best matches (nearest first, distance below max_distance) among entries at least min_travel_m
  /// of path before \p path_m; at most \p max_matches.
  std::vector<PlaceMatch> query(const ScanContext& sc, double path_m, int max_matches = 1) const;
  const ScanContextParams& params() const { return p_; }

 private:
  struct Index;
  ScanContextParams p_;
  std::vector<ScanContext> descs_;
  std::vector<size_t> ids_;
  std::vector<double> path_m_;
  mutable std::unique_ptr<Index> index_;
  mutable size_t indexed_ = 0;  ///< entries in the kd-tree (rebuilt when the eligible ones outgrow it)
};

}  // namespace roadslam::place
