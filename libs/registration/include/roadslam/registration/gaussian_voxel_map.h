#pragma once
/// \file gaussian_voxel_map.h
/// An incremental map of Gaussians on a voxel grid, and scan-to-map registration against it.
///
/// Each voxel accumulates the sum and the scatter of the points that fell in it (so inserting a
/// sweep is O(points), no tree to rebuild) and keeps its mean and a regularised inverse
/// covariance. A source point is paired with the nearest voxel mean among the voxels around it
/// and the residual is weighed by that voxel's information: the point-to-distribution cost of
/// VGICP (Koide et al., ICRA 2021) with a zero source covariance and NDT's covariance
/// regularisation, so it acts point-to-plane on flat voxels and point-to-line on poles.
/// Solved by Gauss-Newton with a Geman-McClure kernel (IRLS), left perturbations [t, w] in the
/// map frame. Frames: points inserted and the result are in the map (world) frame.
/// The default matcher of the odometry; its align() has the shape of every registration method's
/// (registration.h): target, source points, T_target_source guess, settings, one RegistrationResult.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "roadslam/common/voxel_hash.h"
#include "roadslam/registration/point_cloud.h"
#include "roadslam/registration/registration.h"

namespace roadslam::registration {

class GaussianVoxelMap {
 public:
  /// \param voxel_m voxel edge [m]; \param max_points_per_voxel a voxel stops growing there [-];
  /// \param radius_m voxels farther than this from the vehicle are dropped [m]
  /// \param neighbours voxels searched for a pair: 1 (the one holding the point) or 7 (and its faces)
  /// \param ring_lines_on_walls a voxel off the road crossed by one horizontal scan ring constrains
  /// the map across the vertical surface through that ring (else it waits for a second ring)
  GaussianVoxelMap(double voxel_m, int max_points_per_voxel, double radius_m, int neighbours = 7,
                   bool ring_lines_on_walls = true);

  /// Adds points in the map frame [m] and refreshes the statistics of the voxels they touched.
  /// \p is_ground (empty, or one flag per point) marks road-surface points: a voxel crossed by a
  /// single scan ring of road then constrains height (a plane through the ring, level across it);
  /// off the road such a voxel constrains the horizontal direction across the ring (a wall).
  void insert(const std::vector<Eigen::Vector3d>& points_map, const std::vector<uint8_t>& is_ground = {});
  /// Drops voxels whose mean is farther than radius_m from \p origin_map [m].
  void removeFar(const Eigen::Vector3d& origin_map);
  /// Drops the voxels whose mean (map frame [m]) \p drop is true for (a moving object's box); returns
  /// how many. A voxel keeps only sums, not points: it goes whole.
  template <class Pred>
  size_t eraseVoxels(Pred&& drop) {
    size_t n = 0;
    for (auto it = voxels_.begin(); it != voxels_.end();) {
      if (drop(static_cast<const Eigen::Vector3d&>(it->second.mean))) {
        it = voxels_.erase(it);
        ++n;
      } else {
        ++it;
      }
    }
    return n;
  }
  size_t numVoxels() const { return voxels_.size(); }
  bool empty() const { return voxels_.empty(); }
  /// Voxel means [m, map frame] (for pictures and keyframe maps).
  std::vector<Eigen::Vector3d> means() const;

  struct Voxel {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();  ///< sum of p p^T
    int n = 0;
    int ground_n = 0;                                   ///< points labelled ground
    uint32_t batch = 0;                                 ///< last insert() that touched it
    bool valid = false;                                 ///< enough points for a covariance
    /// info comes from a single scan ring (a level plane on the road, an upright one off it): the
    /// ring's place on the surface moves with the sensor, so it is no evidence of the motion
    bool ring_line = false;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d info = Eigen::Matrix3d::Zero();     ///< regularised inverse covariance [1/m^2]
  };
  /// Nearest valid voxel mean to \p x within \p max_dist_m among the searched voxels; nullptr if none.
  const Voxel* nearest(const Eigen::Vector3d& x, double max_dist_m) const;

  /// The valid voxels nearest() searches for a point in the voxel \p key: a point that stays in its
  /// voxel between iterations of an alignment keeps them (no hash look-up). Pointers stay valid
  /// until the next insert() or removeFar().
  struct Candidates {
    Eigen::Vector3i key = Eigen::Vector3i::Constant(std::numeric_limits<int>::min());
    int n = 0;
    const Voxel* voxels[7] = {};
  };
  void candidatesOf(const Eigen::Vector3i& key, Candidates& out) const;
  /// nearest() among \p c.
  static const Voxel* nearestOf(const Candidates& c, const Eigen::Vector3d& x, double max_dist_m);
  Eigen::Vector3i keyOf(const Eigen::Vector3d& p) const {
    return (p * inv_voxel_).array().floor().cast<int>();
  }

 private:
  void refresh(Voxel& v) const;

  double inv_voxel_, radius_m_;
  int max_points_;
  int neighbours_;
  bool ring_lines_on_walls_;
  uint32_t batch_ = 0;
  std::unordered_map<Eigen::Vector3i, Voxel, VoxelKeyHash> voxels_;
};

struct VoxelAlignParams {
  int max_iterations = 30;
  double max_correspondence_distance_m = 2.0;  ///< [m]
  double kernel_scale_m = 0.5;                 ///< Geman-McClure scale on the Mahalanobis-free distance [m]
  double convergence_translation_m = 1e-4;     ///< [m]
  double convergence_rotation_rad = 1e-4;      ///< [rad]
  int min_inliers = 20;
  double max_correction_m = 5.0;               ///< beyond the guess => Diverged [m]
  double degeneracy_threshold = 0.02;          ///< normalised Hessian eigenvalue [-]
};

/// What the scans measured, for judging degeneracy along a direction (Zhang et al., ICRA 2016,
/// "On degeneracy of optimization-based state estimation problems"): the Gauss-Newton Hessian at the
/// result without the tilt prior and without single-ring voxels (GaussianVoxelMap::Voxel::ring_line),
/// whose constraints move with the sensor (a tunnel's ceiling crossed by one ring reads as an
/// upright surface across the tunnel and would hold the vehicle back along its axis).
struct SurfaceInformation {
  Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();  ///< [t, w] left increments, map frame [1/m^2, 1/rad^2, 1/m/rad]
  /// H scaled like RegistrationResult::information (by the inverse squared fitness) [1/m^2, 1/rad^2]
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  int inliers = 0;  ///< all pairs of the final system, ring lines included (the normaliser) [-]
  /// n^T H_tt n / inliers: the information of the translation along the unit vector \p n_map
  /// (map frame), per pair: the fraction of the pairs that measure it [-]
  double along(const Eigen::Vector3d& n_map) const {
    return inliers > 0 ? n_map.dot(H.topLeftCorner<3, 3>() * n_map) / inliers : 0.0;
  }
};

/// One constraint n . g_lidar = 0 on the up direction in the lidar frame (a vertical structure of the
/// sweep: odometry/vertical_structures.h finds them).
struct VerticalConstraint {
  Eigen::Vector3d normal_lidar = Eigen::Vector3d::UnitX();  ///< unit, horizontal when the pose is right
  /// Inverse variance of n . g [1/rad^2]: points x (spread along the structure's vertical)^2 /
  /// (spread across it)^2, the spread across floored at min_thickness_m.
  double weight = 0;
};

/// Absolute tilt prior of the alignment: the sweep's vertical structures (lidar frame) must stand
/// along \p up_map. Each constraint adds the residual (R n) . up [rad] with the weight
/// scale_m2 * VerticalConstraint::weight, under a Geman-McClure kernel of scale kernel_rad so
/// leaning trunks and tilted car sides fade out. scale_m2 turns the constraints' inverse variances
/// [1/rad^2] into the units of the scan residuals [1/m^2]: it sets how hard the prior pulls
/// against the registration's (over-confident, points-as-independent) information.
struct GravityPrior {
  const std::vector<VerticalConstraint>* constraints = nullptr;
  Eigen::Vector3d up_map = Eigen::Vector3d::UnitZ();  ///< unit up direction in the map frame
  double scale_m2 = 1.0;                              ///< [m^2]
  double kernel_rad = 0.035;                          ///< [rad]
};

/// Aligns \p points_source (lidar frame [m]) to \p target from \p T_target_source_guess, with an
/// optional tilt prior; \p surface (optional) receives the scans' information without the ring lines.
/// Never throws on data problems: failures come back with converged=false and a Status.
RegistrationResult align(const GaussianVoxelMap& target, const PointCloud& points_source,
                         const Eigen::Isometry3d& T_target_source_guess, const VoxelAlignParams& params,
                         const GravityPrior* gravity = nullptr, SurfaceInformation* surface = nullptr);

}  // namespace roadslam::registration
