#pragma once
/// \file gnss_fusion.h
/// GNSS positions fused into a trajectory as robust unary factors, in batch: a pose graph
/// whose nodes are the trajectory's poses T_enu_node, whose binary factors are the trajectory's own
/// relative motions (odometry, loop-corrected or dead-reckoned), and whose unary factors are the GNSS
/// antenna positions in a local ENU frame. The map-to-ENU transform T_enu_map is estimated on the way.
///
/// Frames: `map` is the trajectory's frame (the odometry's world frame, z roughly up); `enu` a local
/// East-North-Up frame (libs/gnss EnuFrame); `node` the body whose poses are given (the lidar for
/// roadslam-map, the vehicle for dead reckoning). The antenna sits at the lever arm in the node frame.
///
/// Factors and solver (Gauss-Newton with iteratively reweighted least squares, right perturbations
/// T <- T Exp(d), d = [rho, phi], the pseudo-exponential MRPT's graph SLAM uses: t <- t + R rho):
///  - motion i -> i+1: e = log(Z^-1 T_i^-1 T_j), de/dd_j = I, de/dd_i = -Ad(T_j^-1 T_i) (first order),
///    information diag(1/st^2 I3, 1/sr^2 I3) with st^2 = edge_sigma_t^2 + (edge_sigma_t_per_m d)^2 and
///    sr alike, d the distance between the nodes;
///  - GNSS fix k on node i (the node nearest in time; the antenna offset carried from the fix's time
///    to the node's along the input trajectory): r = R_i p + t_i - z, dr/drho = R_i,
///    dr/dphi = -R_i [p]x, information the fix's covariance^-1, weighted by the robust kernel of its
///    Mahalanobis distance m (Cauchy: w = 1 / (1 + (m/c)^2); Huber: w = min(1, c/m));
///  - a weak roll / pitch prior on the first node (a straight drive leaves the roll about its own
///    line unobserved by positions).
/// The start: T_enu_map by a robust (IRLS) yaw + translation fit of the antenna path to the fixes.

#include <cmath>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::gnss_fusion {

using Matrix6d = Eigen::Matrix<double, 6, 6>;  ///< a motion factor's information, [t, r] order
using PoseVector = std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>;  ///< one per node

enum class RobustKernel { None, Huber, Cauchy };

/// Ini values: gauss_newton (the IRLS Gauss-Newton above, gnss_fusion.cpp) | ceres (the same factors,
/// information and robust kernel as Ceres's loss on its Levenberg-Marquardt, src/gnss_fusion_ceres.cpp;
/// docs/benchmarks.md compares the two).
enum class GnssOptimizer { GaussNewton, Ceres };

/// Ini section [gnss_fusion].
struct GnssFusionParams {
  double lever_x_m = 0, lever_y_m = 0, lever_z_m = 0;  ///< antenna in the node frame [m]
  /// Motion factors: per edge, so their sum over a stretch grows with the square root of the number
  /// of nodes on it. A loose rotation lets the graph bend the path to absorb a scale error instead of
  /// shortening the steps (a synthetic 0.5 % scale error put 4 m into a 30 s outage with 0.05 deg).
  double edge_sigma_t_m = 0.01;          ///< motion factor translation std, sigma_0 [m]
  double edge_sigma_t_per_m = 0.005;     ///< ... growing per metre between the nodes [m/m]
  double edge_sigma_r_rad = 0.01 * M_PI / 180;   ///< rotation std, sigma_0 [rad]; ini edge_sigma_r_deg
  double edge_sigma_r_rad_per_m = 0.002 * M_PI / 180;  ///< ... per metre [rad/m]; ini edge_sigma_r_deg_per_m
  /// Multiplies the motion factors' std of z, roll and pitch (in the node frame): > 1 for a planar
  /// odometry (CAN dead reckoning) that knows nothing of hills [-].
  double edge_vertical_scale = 1.0;
  RobustKernel kernel = RobustKernel::Cauchy;  ///< robust kernel of the GNSS factors
  double kernel_width = 3.0;             ///< c, in Mahalanobis units [-]
  double outlier_gate = 6.0;             ///< a fix whose final Mahalanobis distance exceeds this is counted rejected [-]
  double max_time_offset_s = 0.15;       ///< a fix farther in time from every node is not used [s]
  double attitude_prior_sigma_rad = 2.0 * M_PI / 180;  ///< first node's roll / pitch prior [rad]; ini _deg
  int max_iterations = 30;               ///< Gauss-Newton iterations [-]
  GnssOptimizer optimizer = GnssOptimizer::GaussNewton;  ///< ini optimizer
  double uere_m = 3.0;                   ///< user equivalent range error: sigma = HDOP x uere without GST [m]
  double fallback_sigma_m = 5.0;         ///< sigma of a fix with neither GST nor HDOP [m]
  bool receiver_time = true;             ///< stamp fixes with the receiver's time (else the receive time)
  /// The online (causal) mode, gnss_fusion_online.h: the window of past frames and fixes solved, and
  /// how often it is re-solved; between solves the last correction carries the odometry forward.
  double online_window_s = 60.0;         ///< [s]
  double online_solve_period_s = 1.0;    ///< [s]
  /// A new correction is blended in over this long (linear in translation, slerp in rotation) instead
  /// of jumping: each re-solve moves the newest pose by a few decimetres of noise [s]; 0 = jump.
  double online_blend_s = 1.0;
  /// The first correction waits until the window's path is this long: on a few metres the heading
  /// (and so the position ahead) is poorly observed [m]; 0 = as soon as a solve runs.
  double online_min_path_m = 0.0;
  /// Estimate the odometry's yaw-rate bias in the online mode (gnss_fusion_online.h): a dead reckoning
  /// from a gyro or wheel speeds turns its heading at a constant offset that a 60 s window cannot bend
  /// away under tight rotation factors (the RAV4 drive: -0.4 deg/s, 24 deg over a window).
  bool online_yaw_rate_bias = false;
  /// Estimate the odometry's scale in the online mode alike: wheel speeds off by a few tenths of a
  /// percent put metres into a 60 s window that tight translation factors cannot absorb.
  bool online_odometry_scale = false;
  /// ... the bias and the scale only from windows whose path is at least this long: on less, the
  /// fixes' course and path length are noise [m].
  double online_bias_min_path_m = 100.0;
  /// The live viewer's online correction (pipeline::LiveGnss) fuses the GPS records of this sensor
  /// label only (CAN_GPS, roadslam-grab's receiver GNSS, ...); empty: the first source that gives a
  /// valid fix. Never a mix of receivers. roadslam-map chooses with --gnss-label instead.
  std::string live_source_label;

  Eigen::Vector3d lever() const { return {lever_x_m, lever_y_m, lever_z_m}; }
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "gnss_fusion");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "gnss_fusion") const;
};

/// A GNSS antenna position in the ENU frame.
struct GnssFactor {
  double t_s = 0;               ///< [s], the trajectory's clock
  Eigen::Vector3d p_enu;        ///< [m]
  Eigen::Matrix3d cov;          ///< [m^2]
};

enum class FixUse : unsigned char { Used, Rejected, Unmatched };

struct GnssFusionResult {
  bool ok = false;              ///< false: too few fixes or too little motion (status says which)
  std::string status;
  PoseVector T_enu_node;        ///< fused poses, one per input node
  Eigen::Isometry3d T_enu_map = Eigen::Isometry3d::Identity();  ///< best rigid map -> ENU over the fused nodes
  Eigen::Isometry3d T_enu_map_initial = Eigen::Isometry3d::Identity();  ///< the robust fit the solver started from
  std::vector<FixUse> fix_use;  ///< per input fix
  size_t used = 0, rejected = 0, unmatched = 0;
  int iterations = 0;
  bool converged = false;       ///< the last step moved no node by more than 0.1 mm (else max_iterations ran out)
  double rms_inlier_m = 0;      ///< rms horizontal residual of the used fixes [m]
  double ms = 0;                ///< wall time [ms]
};

/// Fuses \p fixes into the trajectory (\p stamps_s [s], \p T_map_node, same size, stamps increasing).
GnssFusionResult fuseGnss(const std::vector<double>& stamps_s, const PoseVector& T_map_node,
                          const std::vector<GnssFactor>& fixes, const GnssFusionParams& p);

/// T at time \p t along (stamps, poses): linear translation, slerped rotation, clamped at the ends.
Eigen::Isometry3d interpolatePose(const std::vector<double>& stamps_s, const PoseVector& T, double t);

}  // namespace roadslam::gnss_fusion
