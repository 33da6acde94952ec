#pragma once
/// \file global_registration.h
/// Registration with no initial guess (the Open3D pipeline's FPFH + global solver + ICP):
///  1. both clouds voxelised (voxel_m), normals within normal_radius_m oriented to the sensor, FPFH
///     (fpfh.h, Rusu et al. 2009) within feature_radius_m at keypoints: points whose normal is further than
///     level_normal_deg from vertical (road and roofs look alike everywhere: they describe nothing);
///  2. correspondences: mutual nearest neighbours in the 33-D feature space (nanoflann kd-trees);
///  3. RANSAC over triplets of correspondences (Fischler & Bolles 1981), each triplet pruned first by its
///     edge lengths (a rigid motion keeps them: Open3D's CorrespondenceCheckerBasedOnEdgeLength), the pose of
///     a triplet by Kabsch / Umeyama, support = correspondences within inlier_distance_m; the best pose is
///     refitted on its inliers; the best pose at least rival_distance_m / rival_angle_deg away from it is the
///     rival, and confidence = 1 - rival support / best support (0: two places explain the features
///     equally well, as on look-alike parallel streets);
///  4. refinement by the project's registration (registration.h, [..._fine] Params, point-to-plane ICP by
///     default) on the clouds at refine_voxel_m, from the RANSAC pose; when confidence < min_confidence the
///     rival is refined too and the pose pairing more source points wins if its overlap is higher by
///     min_overlap_margin (confidence then = 1 - the other's overlap / its own).
/// Failures are data (RegistrationResult::status and reason): too few points or keypoints, too few
/// correspondences, no consensus, ambiguous (the two poses' overlaps within the margin), the refinement's own
/// failures, a degenerate refinement (a weak direction, e.g. along a corridor), low overlap. A pose is never returned as converged on such an input.

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "roadslam/registration/fpfh.h"
#include "roadslam/registration/params.h"
#include "roadslam/registration/registration.h"

namespace roadslam::registration {

/// Ini section [global_registration]; the refinement reads [global_registration_fine] (Params keys).
struct GlobalParams {
  double voxel_m = 1.0;              ///< feature cloud voxel [m]
  double normal_radius_m = 2.0;      ///< normals from the neighbours within [m]
  double feature_radius_m = 5.0;     ///< FPFH neighbourhood [m]
  int max_feature_neighbours = 0;    ///< nearest neighbours in one histogram, 0: all within the radius [-]
  double level_normal_rad = 25.0 * M_PI / 180.0;  ///< normals within this of vertical are no keypoints [rad]; ini _deg
  int min_keypoints = 20;            ///< fewer keypoints in either cloud: TooFewPoints [-]
  double match_eps = 0.5;            ///< approximate feature search: within (1 + eps) of the nearest [-] (0.5: 10 % faster on KITTI, same successes)
  int min_correspondences = 10;      ///< fewer mutual correspondences: TooFewCorrespondences [-]
  int ransac_max_iterations = 20000; ///< triplets drawn at most [-]
  double ransac_probability = 0.9999; ///< stop once a better triplet is this unlikely to be missed [-]
  double inlier_distance_m = 1.5;    ///< a correspondence supports a pose within this [m]
  double edge_similarity = 0.9;      ///< triplet edges must keep this ratio source/target [-]
  double min_edge_m = 1.0;           ///< triplet edges shorter than this are drawn again [m]
  int min_consensus = 8;             ///< fewer supporting correspondences: NoConsensus [-]
  double rival_distance_m = 2.0;     ///< a rival pose is this far from the best ... [m]
  double rival_angle_rad = 10.0 * M_PI / 180.0;  ///< ... or turned this much [rad]; ini _deg
  double min_confidence = 0.25;      ///< 1 - rival/best support below: both poses refined, decided by overlap [-]
  double min_overlap_margin = 0.1;   ///< ... the better overlap must exceed the other's by this, else Ambiguous [-]
  double refine_voxel_m = 0.5;       ///< refinement clouds' voxel [m]
  double min_overlap = 0.3;          ///< refined inliers / source points below: LowOverlap [-]
  bool reject_degenerate = true;     ///< a refinement with a weak direction (Degeneracy) is Ambiguous [-]
  unsigned seed = 42;                ///< RANSAC random seed [-]
  Params fine;                       ///< refinement: point-to-plane ICP, 1 m reach by default

  GlobalParams();
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "global_registration");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "global_registration") const;
};

/// A kd-tree over one cloud's FPFH descriptors (built once, queried by every pair the cloud enters).
class FeatureIndex;

/// A cloud prepared for global registration: everything a pair needs that depends on one cloud only
/// (features, their kd-tree, the refinement's target structures), computed once per keyframe and reused
/// for many pairs, so a pair costs only the matching, RANSAC and the refinement.
struct FeatureCloud {
  PointCloud points;           ///< at GlobalParams::voxel_m, the cloud's frame [m]
  std::vector<int> keypoints;  ///< indices into points [-]
  std::vector<Fpfh> features;  ///< one per keypoint
  PointCloud refine_points;    ///< at GlobalParams::refine_voxel_m [m]
  size_t input_points = 0;     ///< finite points given [-]
  /// kd-tree over features (owns a copy of them); null: built per pair
  std::shared_ptr<const FeatureIndex> index;
  /// refine_points as the refinement's target (GlobalParams::fine); null: built per pair
  std::shared_ptr<const Target> refine_target;
};

/// Features of \p points (its own frame, the sensor at the origin [m]; non-finite points dropped), with
/// the feature kd-tree and the refinement target built for \p params (use the FeatureCloud with the
/// same params only). \p as_target false leaves refine_target null (a cloud only ever registered as the
/// source needs none).
FeatureCloud computeFeatures(const PointCloud& points, const GlobalParams& params, bool as_target = true);

/// What the global stage found, for benchmarks and diagnostics.
struct GlobalDiagnostics {
  int correspondences = 0;     ///< mutual nearest neighbours in feature space [-]
  int consensus = 0;           ///< correspondences supporting the best pose [-]
  int rival_consensus = 0;     ///< ... the best pose far from it [-]
  int hypotheses = 0;          ///< triplets that passed the edge test and were scored [-]
  Eigen::Isometry3d T_ransac = Eigen::Isometry3d::Identity();  ///< before refinement
  Eigen::Isometry3d T_rival = Eigen::Isometry3d::Identity();   ///< the rival pose (when rival_consensus > 0)
  double features_ms = 0, match_ms = 0, ransac_ms = 0, refine_ms = 0;  ///< wall time per stage [ms]
};

/// T_target_source with no initial guess. RegistrationResult::confidence is 1 - rival/best support;
/// inliers, fitness, information and degeneracy come from the refinement.
RegistrationResult alignGlobal(const FeatureCloud& target, const FeatureCloud& source, const GlobalParams& params,
                               GlobalDiagnostics* diagnostics = nullptr);

/// Convenience: features of both, then alignGlobal.
RegistrationResult alignGlobal(const PointCloud& points_target, const PointCloud& points_source,
                               const GlobalParams& params, GlobalDiagnostics* diagnostics = nullptr);

}  // namespace roadslam::registration
