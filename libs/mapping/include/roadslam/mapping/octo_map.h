#pragma once
/// \file octo_map.h
/// OctoMap (Hornung et al. 2013) of the keyframes: occupied voxels at the scan end points, free
/// voxels along the rays (map frame, metres). Our keyframe insertion gives the same log-odds update
/// as octomap::OcTree::insertPointCloud (discretised: one ray per distinct end-point voxel, a voxel
/// hit by any end point is never marked free in the same scan, as octomap's computeUpdate), but
///  - casts the rays with a 3D DDA (Amanatides & Woo 1987) into a flat key vector sorted once
///    (no per-cell hash insertion), and
///  - updates the tree with lazy evaluation and one updateInnerOccupancy() per keyframe,
/// which is where octomap's own insertion spends its time. Free space is cleared up to
/// free_max_range_m along each ray (longer rays clear their first free_max_range_m only).

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}
namespace octomap {
class OcTree;
}

namespace roadslam::mapping {

/// Ini section [octomap].
struct OctoMapParams {
  bool enabled = true;
  double resolution_m = 0.2;      ///< leaf size [m]
  double max_range_m = 60.0;      ///< end points farther from the sensor are dropped [m]
  double free_max_range_m = 10.0; ///< free space cleared up to this distance along a ray [m]
  double prob_hit = 0.7;          ///< occupancy probability of a hit [-]
  double prob_miss = 0.4;         ///< ... of a pass-through [-]
  double clamp_min = 0.12;        ///< log-odds clamping, as probabilities [-]
  double clamp_max = 0.97;        ///< [-]
  bool write_ot = false;          ///< also write map.ot (full probabilities) beside map.bt
  double keyframe_spacing_m = 10.0;  ///< keyframes inserted into the run's map are this far apart [m]

  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "octomap");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "octomap") const;
};

struct InsertStats {
  size_t points = 0;         ///< end points used [-]
  size_t occupied_keys = 0;  ///< distinct voxels updated as occupied [-]
  size_t free_keys = 0;      ///< distinct voxels updated as free [-]
  double ms = 0;             ///< wall time [ms]
};

/// Agreement of two maps over the voxels the reference knows (sampled at its leaf centres).
struct Agreement {
  size_t ref_occupied = 0, ref_free = 0;      ///< known leaves of the reference [-]
  double occupied_percent = 0;                ///< of those, also occupied in the other map [%]
  double free_percent = 0;                    ///< of those, also free in the other map [%]
};

class OctoMapBuilder {
 public:
  explicit OctoMapBuilder(OctoMapParams params = {});
  ~OctoMapBuilder();
  OctoMapBuilder(OctoMapBuilder&&) noexcept;
  OctoMapBuilder& operator=(OctoMapBuilder&&) noexcept;

  /// Our insertion: \p points_lidar in the lidar frame [m], sensor pose \p T_map_lidar.
  InsertStats insert(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_map_lidar);
  /// octomap's own OcTree::insertPointCloud (same max range), for comparison and tests.
  InsertStats insertReference(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_map_lidar);
  void clear();

  const octomap::OcTree& tree() const;
  const OctoMapParams& params() const { return p_; }
  size_t numLeafs() const;
  /// Writes the max-likelihood binary map (.bt) of a copy, leaving this tree untouched
  /// (OcTree::writeBinaryConst), to a temporary name renamed on success; throws naming the path.
  void writeBt(const std::string& path) const;
  /// Writes the full-probability map (.ot) atomically; throws naming the path.
  void writeOt(const std::string& path) const;

 private:
  OctoMapParams p_;
  std::unique_ptr<octomap::OcTree> tree_;
};

/// Compares \p other with \p reference (see Agreement).
Agreement compareOctoMaps(const octomap::OcTree& reference, const octomap::OcTree& other);

}  // namespace roadslam::mapping
