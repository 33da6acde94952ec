#pragma once
/// \file seen_through.h
/// Visibility-based removal of dynamic points from the keyframes, a map-building pass run once the
/// trajectory is known (ini section [seen_through]). A map point is dynamic when other sweeps see
/// through it: at the point's pixel of a keyframe's range image the measured range lies well beyond
/// the point (Kim & Kim, "Remove, then Revert", IROS 2020; Pomerleau et al., ICRA 2014; Schauer &
/// Nuechter, RA-L 2018). It removes what tracking cannot label: cars too far or too sparse for an
/// object, and the first sweeps of a car before its moving label.
///
/// The test is run per map voxel (x-y-z, [point_map] voxel_m) over the voxels above the local ground:
///   - ground height of an x-y cell = the lowest map point in it; voxels less than min_height_m above
///     it are not tested (the ground, seen at grazing angles, is the false positive of this test);
///   - each reference keyframe (one per reference_spacing_m of path) builds a range image (azimuth x
///     elevation, nearest range per pixel) of its own points and projects every tested voxel within
///     max_range_m of its lidar: seen through when the pixel's range, and its azimuth_window neighbours'
///     on each side, exceed the voxel's by margin_m + margin_ratio * range (a thin pole a neighbour ray
///     hits stays); hit when the pixel's range is within that margin of it; empty pixels say nothing;
///   - dynamic: seen through by at least min_through sweeps and by more than through_hit_ratio times as
///     many as hit it.
/// The dynamic voxels' points leave every keyframe; the maps built afterwards (point map, OctoMap,
/// grid, map folder) lose them.

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <unordered_set>

#include "roadslam/common/voxel_hash.h"
#include "roadslam/mapping/loop_closure.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::mapping {

class Mapper;

/// Ini section [seen_through].
struct SeenThroughParams {
  bool enabled = false;              ///< run the pass before the maps are written [-]
  double azimuth_res_rad = 1.0 * 3.14159265358979323846 / 180.0;    ///< range-image column width; ini `azimuth_res_deg` [rad]
  double elevation_res_rad = 1.0 * 3.14159265358979323846 / 180.0;  ///< range-image row height; ini `elevation_res_deg` [rad]
  int azimuth_window = 1;            ///< columns either side that must be seen through too [-]
  double margin_m = 1.0;             ///< seen through: measured range beyond the point's by this ... [m]
  double margin_ratio = 0.05;        ///< ... plus this fraction of the point's range [-]
  /// ... and the pixel's ray (its nearest point's elevation) passes this close to the voxel vertically [m]
  double ray_tolerance_m = 0.15;
  double max_range_m = 100.0;        ///< voxels farther from a reference lidar are not tested by it [m]
  double min_height_m = 0.3;         ///< voxels at least this high above their cell's ground are tested (0: all) [m]
  double ground_cell_m = 1.0;        ///< x-y cell of the ground height (lowest map point) [m]
  double reference_spacing_m = 2.0;  ///< reference keyframes at least this much path apart [m]
  int min_through = 2;               ///< dynamic: seen through by at least this many references ... [-]
  double through_hit_ratio = 3.0;    ///< ... and by more than this times the references that hit it (the roof of a parked car, seen at grazing incidence, is seen through by the rays just over it) [-]

  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "seen_through");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "seen_through") const;
};

/// Counts of one pass.
struct SeenThroughStats {
  size_t voxels = 0;          ///< map voxels [-]
  size_t tested_voxels = 0;   ///< above the ground [-]
  size_t references = 0;      ///< keyframes whose range image was used [-]
  size_t dynamic_voxels = 0;  ///< [-]
  size_t removed_points = 0;  ///< keyframe points removed [-]
  double ms = 0;              ///< wall time [ms]
};

/// The dynamic voxels (keys at \p voxel_m in the map frame) of keyframes \p kfs at poses \p T_map_kf.
std::unordered_set<Eigen::Vector3i, VoxelKeyHash> findSeenThrough(const std::vector<Keyframe>& kfs,
                                                                  const PoseVector& T_map_kf, double voxel_m,
                                                                  const SeenThroughParams& p,
                                                                  SeenThroughStats* stats = nullptr);

/// Runs findSeenThrough on \p mapper's keyframes at its optimised poses and erases the dynamic voxels'
/// points from them.
SeenThroughStats removeSeenThrough(Mapper& mapper, double voxel_m, const SeenThroughParams& p);

}  // namespace roadslam::mapping
