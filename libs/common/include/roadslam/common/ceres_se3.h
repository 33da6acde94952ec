#pragma once
// Residuals shared by the Ceres solvers (libs/mapping's pose_graph_ceres.cpp, libs/gnss_fusion's
// gnss_fusion_ceres.cpp): a node is a translation t (R^3) and a unit quaternion q (Eigen's x, y, z, w
// order, EigenQuaternionManifold). Header only: libs/common does not link Ceres, a target that
// includes this links Ceres::ceres itself.
#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace roadslam::ceres_se3 {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// S with S^T S = W for a symmetric positive semi-definite W (S = sqrt(Lambda) V^T), so that
/// |S e|^2 = e^T W e.
inline Matrix6d sqrtInformation(const Matrix6d& W) {
  Eigen::SelfAdjointEigenSolver<Matrix6d> es(0.5 * (W + W.transpose()));
  return es.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal() * es.eigenvectors().transpose();
}

/// Binary factor on (t_i, q_i, t_j, q_j), measurement Z = T_i_j with information W in [t, r] order:
/// r = S [t_E; Log(R_E)], E = Z^-1 T_i^-1 T_j (MRPT's pseudo-logarithm, mapping's pose_graph_solver.h).
struct RelativePoseResidual {
  Eigen::Quaterniond q_Z_inv;
  Eigen::Vector3d t_Z;
  Matrix6d S;

  template <typename T>
  bool operator()(const T* ti, const T* qi, const T* tj, const T* qj, T* out) const {
    using Q = Eigen::Quaternion<T>;
    using V = Eigen::Matrix<T, 3, 1>;
    const Eigen::Map<const Q> Qi(qi), Qj(qj);
    const Eigen::Map<const V> Ti(ti), Tj(tj);
    const Q q_ij = Qi.conjugate() * Qj;                         // R_i^T R_j
    const V t_ij = Qi.conjugate() * (Tj - Ti);                  // R_i^T (t_j - t_i)
    const Q q_E = q_Z_inv.cast<T>() * q_ij;                     // R_Z^T R_ij
    const V t_E = q_Z_inv.cast<T>() * (t_ij - t_Z.cast<T>());   // R_Z^T (t_ij - t_Z)
    const T wxyz[4] = {q_E.w(), q_E.x(), q_E.y(), q_E.z()};
    Eigen::Matrix<T, 6, 1> e;
    e.template head<3>() = t_E;
    ceres::QuaternionToAngleAxis(wxyz, e.data() + 3);          // Log(R_E), angle in [-pi, pi]
    Eigen::Map<Eigen::Matrix<T, 6, 1>> r(out);
    r = S.cast<T>() * e;
    return true;
  }

  static ceres::CostFunction* create(const Eigen::Isometry3d& Z, const Matrix6d& W) {
    return new ceres::AutoDiffCostFunction<RelativePoseResidual, 6, 3, 4, 3, 4>(new RelativePoseResidual{
        Eigen::Quaterniond(Z.rotation()).normalized().conjugate(), Z.translation(), sqrtInformation(W)});
  }
};

}  // namespace roadslam::ceres_se3
