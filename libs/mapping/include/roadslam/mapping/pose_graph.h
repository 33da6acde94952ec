#pragma once
/// \file pose_graph.h
/// 3D pose graph of keyframes: MRPT's CNetworkOfPoses3DInf (the store and its VERTEX3/EDGE3 text
/// format) optimised by our sparse Levenberg-Marquardt (src/pose_graph_solver.h; [pose_graph] optimizer
/// = mrpt_levmarq runs mrpt::graphslam::optimize_graph_spa_levmarq instead). The MRPT headers stay in
/// pose_graph.cpp (graphslam/levmarq.h alone costs ~4 s per translation unit); optimizer = ceres runs
/// the same model on Ceres (src/pose_graph_ceres.cpp).
///
/// Frames: node i holds T_map_keyframe_i (map = world frame of the odometry, anchored at node 0,
/// which stays fixed). Edge (i, j) measures T_i_j = T_map_i^-1 * T_map_j. Information matrices are
/// 6x6 in the order [tx ty tz rx ry rz] (m, rad) of the residual plog(T_i_j^-1 T_map_i^-1 T_map_j) =
/// [t; rotation vector], MRPT's pseudo-logarithm, an error in the frame of node j as the edge predicts
/// it (a right perturbation of the measurement), which is also the order and frame of
/// registration::RegistrationResult::information for T_target_source.

#include <cmath>
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::mapping {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using PoseVector = std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>;

/// Ini values: lm (ours: steps accepted on the information-weighted cost, pose_graph_solver.h) |
/// mrpt_levmarq (MRPT 2.5.8's optimize_graph_spa_levmarq, which accepts steps on the unweighted error
/// and stalls when edges' information differs by orders of magnitude; kept for comparison) |
/// ceres (the same residuals and information as lm on Ceres's Levenberg-Marquardt with sparse
/// Cholesky, src/pose_graph_ceres.cpp; docs/benchmarks.md compares the two).
enum class GraphOptimizer { Lm, MrptLevmarq, Ceres };

/// Ini section [pose_graph].
struct PoseGraphParams {
  int max_iterations = 100;               ///< Levenberg-Marquardt iterations per optimisation [-]
  GraphOptimizer optimizer = GraphOptimizer::Lm;  ///< ini optimizer
  bool use_registration_information = true;  ///< odometry edges carry the registration information
  double odometry_information_scale = 1.0;   ///< multiplies the registration information [-]
  /// Keep the registration information's directions (false), or only its translation and rotation
  /// magnitudes (true: each 3x3 block replaced by its mean eigenvalue times identity), so a loop's
  /// correction is not pushed into the few edges whose ground constraint happened to be weakest.
  bool isotropic_information = true;
  /// With isotropic_information: an eigen-direction of the translation or rotation block weaker than
  /// this fraction of the block's strongest keeps its own (weak) information instead of the block's
  /// mean, so a direction the scans could not measure (a tunnel's axis) stays unmeasured in the graph
  /// and a CAN edge or a loop can correct it [-]. 0 = off (every direction gets the mean).
  double isotropic_weak_ratio = 0.0;
  double odometry_sigma_t_m = 0.05;       ///< fallback / floor std of an odometry edge translation [m]
  double odometry_sigma_r_rad = 0.29 * M_PI / 180.0;    ///< ... and rotation [rad]; ini odometry_sigma_r_deg
  /// Wheel-odometry (CAN) constraints between consecutive keyframes (Mapper with a WheelMotion per
  /// frame), fused into the keyframe edge (fuseMeasurements). Planar: strong in base x, y, yaw, weak
  /// in z, roll, pitch; the std grows with the distance d between the keyframes:
  /// sigma = sqrt(sigma_0^2 + (k d)^2).
  bool can_edges = false;
  double can_sigma_t_m = 0.02;            ///< sigma_0 of base x, y [m]
  double can_sigma_t_per_m = 0.01;        ///< k of base x, y [m/m]
  double can_sigma_yaw_rad = 0.001;      ///< sigma_0 of yaw [rad]; ini can_sigma_yaw_deg
  double can_sigma_yaw_rad_per_m = 0.0005; ///< k of yaw [rad/m]; ini can_sigma_yaw_deg_per_m
  double can_weak_information = 1e-4;     ///< information of base z, roll, pitch [1/m^2, 1/rad^2]

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "pose_graph");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "pose_graph") const;
};

struct OptimizeStats {
  int iterations = 0;       ///< LM iterations run [-]
  double final_error = 0;   ///< sum of squared Mahalanobis residuals at the end [-] (mrpt_levmarq: unweighted)
  double ms = 0;            ///< wall time [ms]
};

/// Information-weighted fusion of two measurements of one relative pose, in the tangent space of
/// \p T_a (first order, the pseudo-logarithm MRPT's optimiser uses: translation as is, rotation
/// vector): T = T_a * pexp((I_a + I_b)^-1 I_b log(T_a^-1 T_b)); the fused information is I_a + I_b.
/// Used instead of two parallel edges: MRPT 2.5.8's optimize_graph_spa_levmarq accepts or rejects a
/// step on the unweighted squared error (levmarq_impl.h computeJacobiansAndErrors), so edges that
/// disagree with very different information stall it far from the weighted optimum (a 20-node chain
/// with such parallel edges ended with every edge shorter than both of its measurements).
Eigen::Isometry3d fuseMeasurements(const Eigen::Isometry3d& T_a, const Matrix6d& I_a, const Eigen::Isometry3d& T_b,
                                   const Matrix6d& I_b);

/// A registration's information (registration.h: left perturbations in the target frame, exp(delta) *
/// T_target_source) as the graph's (right perturbations, T_target_source * pexp(e), the edge residual's
/// frame): Ad^T I Ad with Ad the SE(3) adjoint of \p T_target_source in [t, r] order. Translation blocks
/// keep their directions only when the two frames are aligned; a turned revisit rotates them.
Matrix6d sourceFrameInformation(const Matrix6d& I_target, const Eigen::Isometry3d& T_target_source);

class PoseGraph {
 public:
  explicit PoseGraph(PoseGraphParams params = {});
  ~PoseGraph();
  PoseGraph(PoseGraph&&) noexcept;
  PoseGraph& operator=(PoseGraph&&) noexcept;

  /// Adds a node with initial estimate T_map_node; returns its id (0, 1, ...). Node 0 is fixed.
  size_t addNode(const Eigen::Isometry3d& T_map_node);
  /// Adds the measurement T_from_to with its information [1/m^2, 1/rad^2]; returns the edge index.
  size_t addEdge(size_t from, size_t to, const Eigen::Isometry3d& T_from_to, const Matrix6d& information);
  /// Removes the most recently added edge (a loop that failed its consistency check).
  void removeLastEdge();

  OptimizeStats optimize();

  size_t numNodes() const;
  size_t numEdges() const;
  Eigen::Isometry3d pose(size_t node) const;  ///< T_map_node
  PoseVector poses() const;
  /// Restores node estimates (e.g. the state before a rejected loop); size must equal numNodes().
  void setPoses(const PoseVector& T_map_nodes);
  /// Squared Mahalanobis residual of edge \p e at the current estimates [-].
  double edgeChi2(size_t e) const;

  /// Writes MRPT's text graph format (VERTEX3 / EDGE3 lines) atomically; throws naming the path.
  void saveToTextFile(const std::string& path) const;
  /// Information of an odometry edge from the registration's information, already in the keyframe's
  /// lidar frame (sourceFrameInformation of the odometry's, which is about its map frame; see PoseGraphParams).
  Matrix6d odometryInformation(const Matrix6d& registration_information) const;
  /// Information of a CAN edge over \p distance_m [m] in the lidar frame: the base-frame information
  /// (PoseGraphParams can_*) moved through the mounting T_base_lidar, I_lidar = Ad^T I_base Ad with
  /// Ad the SE(3) adjoint of T_base_lidar (a base error e_b = Ad e_lidar, order [t, r]).
  Matrix6d canInformation(double distance_m, const Eigen::Isometry3d& T_base_lidar) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace roadslam::mapping
