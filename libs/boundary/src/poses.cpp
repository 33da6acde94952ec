#include "roadslam/boundary/poses.h"

#include <algorithm>
#include <cmath>

namespace roadslam::boundary {

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

void deskewBetween(Scan& scan, const Eigen::Isometry3d& T_map_start, const Eigen::Isometry3d& T_map_end,
                   double duration_s, const Eigen::Isometry3d& T_map_ref) {
  if (!scan.has_point_times || duration_s <= 0) return;
  const Eigen::Isometry3d T_ref_map = T_map_ref.inverse();
  // Poses per 0.5 ms bucket: slerp per point would cost more than the rest of the detector.
  constexpr int kBuckets = 200;
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> T(kBuckets + 1);
  for (int b = 0; b <= kBuckets; ++b) T[b] = T_ref_map * interpolate(T_map_start, T_map_end, double(b) / kBuckets);
  for (auto& q : scan.points) {
    const int b = std::clamp(static_cast<int>(std::lround(q.t / duration_s * kBuckets)), 0, kBuckets);
    const Eigen::Vector3d v = T[b] * Eigen::Vector3d(q.x, q.y, q.z);
    q.x = static_cast<float>(v.x()), q.y = static_cast<float>(v.y()), q.z = static_cast<float>(v.z());
  }
}

}  // namespace roadslam::boundary
