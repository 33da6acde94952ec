#pragma once
/// \file localizer.h
/// Localization in a prior map: each sweep is registered against a map folder's keyframes
/// (mapping/map_folder.h) without growing the map. Tracking: point-to-plane ICP of the sweep against the whole map
/// (one kd-tree built once) from the constant-velocity prediction. Relocalization, from an unknown start or
/// after a failure (a "kidnapped" vehicle): the sweep's Scan Context against the map's keyframes, each
/// candidate registered with no guess (global_registration.h) and then refined against the map. Every sweep
/// reports a status and a confidence (the refined alignment's overlap: source points with a map point
/// within reach). Frames: map = the prior map's frame; lidar = the sweep's.

#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "roadslam/mapping/map_folder.h"
#include "roadslam/registration/global_registration.h"
#include "roadslam/registration/registration.h"

namespace roadslam::localization {

/// Ini sections [localization] and [localization_track] (registration::Params keys); the relocalization's
/// global registration is the loop closure's ([loop_closure_global], set by the caller).
struct LocalizerParams {
  double map_voxel_m = 0.4;          ///< map points kept: one per voxel [m]
  double sweep_voxel_m = 1.0;        ///< tracking source: one point per voxel [m]
  double min_overlap = 0.5;          ///< tracking / relocalization accepted above this overlap [-]
  int relocalize_candidates = 3;     ///< Scan Context candidates tried per relocalization [-]
  double relocalize_max_distance = 0.3;  ///< Scan Context distance of a relocalization candidate below [-]
  registration::Params track;        ///< point-to-plane ICP, 1 m reach
  registration::GlobalParams global; ///< relocalization's global registration

  LocalizerParams();
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "localization");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "localization") const;
};

enum class LocalizationStatus {
  Tracked,      ///< ICP from the prediction converged with enough overlap
  Relocalized,  ///< found again by place recognition + global registration
  Lost          ///< neither: no pose for this sweep
};
std::string toString(LocalizationStatus s);

struct LocalizationResult {
  LocalizationStatus status = LocalizationStatus::Lost;
  Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();  ///< valid unless Lost
  double confidence = 0;        ///< overlap of the final alignment [0, 1]
  size_t keyframe = 0;          ///< Relocalized: the map keyframe it was found at [-]
  int weak_directions = 0;      ///< directions the final alignment leaves unconstrained (Degeneracy) [-]
  std::string reason;           ///< Lost: why
};

class Localizer {
 public:
  Localizer(mapping::MapFolder map, LocalizerParams p = {});
  ~Localizer();
  /// Localizes one deskewed sweep (lidar frame [m]). Tracks from the prediction when the previous sweep
  /// was localized, relocalizes otherwise or when tracking fails.
  LocalizationResult localize(const std::vector<Eigen::Vector3d>& points_lidar);
  /// Forget the motion (an unknown start, or a known kidnapping): the next sweep relocalizes.
  void reset();
  size_t mapPoints() const;

 private:
  LocalizationResult track(const registration::PointCloud& src, const Eigen::Isometry3d& guess) const;
  LocalizationResult relocalize(const std::vector<Eigen::Vector3d>& points_lidar, const registration::PointCloud& src) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace roadslam::localization
