#pragma once
/// \file octo_map.h
/// OctoMap (Hornung et al. 2013) of the keyframes: occupied voxels at the scan end points, free
/// voxels along the rays (map frame, metres). Our keyframe insertion gives octomap's own update
/// (OcTree::insertPointCloud: one ray per end point, cast with octomap's DDA arithmetic, each voxel
/// updated once per scan, a voxel hit by an end point never freed by the same scan, log-odds
/// clamped), but keeps the occupancy in a flat hashed voxel grid (8x8x8 blocks of float log-odds,
/// a per-scan "touched" bit per voxel) updated in O(1) per ray cell. The octomap::OcTree is
/// materialised from the grid only when it is read (tree(), numLeafs(), writeBt(), writeOt()):
/// cached, pruned, rebuilt after the next insert. Free space is cleared up to free_max_range_m
/// along each ray (longer rays clear their first free_max_range_m only; with free_max_range_m =
/// max_range_m the map equals octomap's).
/// A builder is used by one thread at a time: even the const readers fill the tree cache.

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
namespace roadslam {
class ParamTable;
}

namespace roadslam::mapping::detail {
class VoxelGrid;
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

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "octomap");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "octomap") const;
};

struct InsertStats {
  size_t points = 0;         ///< finite end points (beyond max range: free space only) [-]
  size_t occupied_keys = 0;  ///< distinct voxels updated as occupied [-]
  size_t free_keys = 0;      ///< distinct voxels updated as free [-]
  size_t ray_cells = 0;      ///< cells visited along the rays, repeats included [-]
  double ms = 0;             ///< wall time [ms]
};

/// Agreement of two maps over the voxels the reference knows (sampled at its leaf centres), and
/// the other map's leaves the reference does not know.
struct Agreement {
  size_t ref_occupied = 0, ref_free = 0;      ///< known leaves of the reference [-]
  double occupied_percent = 0;                ///< of those, also occupied in the other map [%]
  double free_percent = 0;                    ///< of those, also free in the other map [%]
  size_t other_unknown = 0;                   ///< leaves of the other map unknown to the reference [-]
};

class OctoMapBuilder {
 public:
  explicit OctoMapBuilder(OctoMapParams params = {});
  ~OctoMapBuilder();
  OctoMapBuilder(OctoMapBuilder&&) noexcept;
  OctoMapBuilder& operator=(OctoMapBuilder&&) noexcept;

  /// Our insertion: \p points_lidar in the lidar frame [m], sensor pose \p T_map_lidar.
  InsertStats insert(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_map_lidar);
  /// octomap's own OcTree::insertPointCloud (same max range; free space up to it, whatever
  /// free_max_range_m says) on the tree, for comparison and tests. Mixing it with insert() works
  /// (the grid is re-read from the tree) but is slow.
  InsertStats insertReference(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_map_lidar);
  void clear();

  /// The map as a pruned octomap tree (materialised on the first read after an insert()).
  const octomap::OcTree& tree() const;
  const OctoMapParams& params() const { return p_; }
  size_t numLeafs() const;   ///< leaves of tree() (pruned) [-]
  size_t numVoxels() const;  ///< known voxels at the leaf resolution [-]
  size_t gridBytes() const;  ///< memory held by the voxel grid [bytes]
  /// Writes the max-likelihood binary map (.bt) of a copy, leaving this tree untouched
  /// (OcTree::writeBinaryConst), to a temporary name renamed on success; throws naming the path.
  void writeBt(const std::string& path) const;
  /// Writes the full-probability map (.ot) atomically; throws naming the path.
  void writeOt(const std::string& path) const;

 private:
  void materialiseTree() const;
  void importTree();
  std::unique_ptr<octomap::OcTree> newTree() const;

  OctoMapParams p_;
  std::unique_ptr<detail::VoxelGrid> grid_;       ///< authoritative after insert()
  mutable std::unique_ptr<octomap::OcTree> tree_;  ///< authoritative after insertReference()
  mutable bool tree_current_ = true;  ///< tree_ holds the grid's content
  bool grid_current_ = true;          ///< grid_ holds the tree's content
};

/// Compares \p other with \p reference (see Agreement).
Agreement compareOctoMaps(const octomap::OcTree& reference, const octomap::OcTree& other);

}  // namespace roadslam::mapping
