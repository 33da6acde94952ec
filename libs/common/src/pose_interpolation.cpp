#include "roadslam/common/pose_interpolation.h"

#include <algorithm>

namespace roadslam {

Eigen::Isometry3d interpolate(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double u) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  T.linear() = qa.slerp(u, qb).normalized().toRotationMatrix();
  T.translation() = (1 - u) * a.translation() + u * b.translation();
  return T;
}

std::optional<Eigen::Isometry3d> interpolatePose(
    const std::vector<double>& st, const std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>& poses,
    double t, double max_gap_s) {
  if (st.empty() || st.size() != poses.size()) return std::nullopt;
  if (t <= st.front()) return t >= st.front() - max_gap_s ? std::optional(poses.front()) : std::nullopt;
  if (t >= st.back()) return t <= st.back() + max_gap_s ? std::optional(poses.back()) : std::nullopt;
  const size_t k = static_cast<size_t>(std::upper_bound(st.begin(), st.end(), t) - st.begin());
  const double dt = st[k] - st[k - 1];
  if (dt > max_gap_s) return std::nullopt;
  return interpolate(poses[k - 1], poses[k], dt > 0 ? (t - st[k - 1]) / dt : 0.0);
}

}  // namespace roadslam
