#include "roadslam/odometry/weak_directions.h"

#include <algorithm>
#include <vector>

namespace roadslam::odometry {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

WeakBasis weakBasis(const registration::Degeneracy& d, const Eigen::Vector3d* n_motion_map) {
  std::vector<Vector6d> cols;
  const auto add = [&](Vector6d v) {  // Gram-Schmidt: the motion often is one of the weak eigenvectors
    for (const auto& c : cols) v -= c.dot(v) * c;
    if (v.norm() > 1e-6) cols.push_back(v.normalized());
  };
  for (int i = 0; i < d.num_weak; ++i) add(d.directions.col(i));
  if (n_motion_map) add((Vector6d() << *n_motion_map, Eigen::Vector3d::Zero()).finished());
  WeakBasis W(6, static_cast<int>(cols.size()));
  for (size_t i = 0; i < cols.size(); ++i) W.col(static_cast<int>(i)) = cols[i];
  return W;
}

Matrix6d reduceInformation(const Matrix6d& information, const Matrix6d& measured, const WeakBasis& weak,
                           double lever_m) {
  if (weak.cols() == 0) return information;
  // In [t, lever * w] coordinates x_s = S^-1 x the information is S I S, S = diag(1, 1, 1, 1/lever ...).
  Vector6d s;
  s << 1, 1, 1, 1 / lever_m, 1 / lever_m, 1 / lever_m;
  const Matrix6d I = s.asDiagonal() * information * s.asDiagonal();
  const Matrix6d M = s.asDiagonal() * measured * s.asDiagonal();
  const Matrix6d P = Matrix6d::Identity() - weak * weak.transpose();
  Matrix6d out = P * I * P;
  for (int i = 0; i < weak.cols(); ++i) {
    const Vector6d w = weak.col(i);
    out += std::clamp(w.dot(M * w), 0.0, w.dot(I * w)) * w * w.transpose();
  }
  return s.cwiseInverse().asDiagonal() * out * s.cwiseInverse().asDiagonal();
}

}  // namespace roadslam::odometry
