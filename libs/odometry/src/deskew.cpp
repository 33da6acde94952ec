#include "roadslam/odometry/deskew.h"

#include <algorithm>
#include <cmath>

#include "roadslam/common/pose_interpolation.h"

namespace roadslam::odometry {

std::vector<Eigen::Vector3d> deskew(const Scan& scan, const Eigen::Isometry3d& delta_T_start_end,
                                    double sweep_duration_s, double reference_fraction) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(scan.points.size());
  const Eigen::Quaterniond q_end(delta_T_start_end.rotation());
  const Eigen::Quaterniond q_id = Eigen::Quaterniond::Identity();
  const Eigen::Vector3d t_end = delta_T_start_end.translation();
  const double inv_dt = sweep_duration_s > 0 ? 1.0 / sweep_duration_s : 0.0;
  for (const auto& p : scan.points) {
    const Eigen::Vector3d x(p.x, p.y, p.z);
    if (!scan.has_point_times) {
      out.push_back(x);
      continue;
    }
    // pose at time t in the reference frame: the constant-velocity motion scaled by (t - t_ref)/dt
    // (slerp extrapolates for negative fractions)
    const double s = static_cast<double>(p.t) * inv_dt - reference_fraction;
    out.push_back(q_id.slerp(s, q_end) * x + s * t_end);
  }
  return out;
}

void deskewBetween(Scan& scan, const Eigen::Isometry3d& T_map_start, const Eigen::Isometry3d& T_map_end,
                   double duration_s, const Eigen::Isometry3d& T_map_ref) {
  if (!scan.has_point_times || duration_s <= 0) return;
  const Eigen::Isometry3d T_ref_map = T_map_ref.inverse();
  // Poses per 0.5 ms bucket: slerp per point would cost more than the boundary detector.
  constexpr int kBuckets = 200;
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> T(kBuckets + 1);
  for (int b = 0; b <= kBuckets; ++b) T[b] = T_ref_map * interpolate(T_map_start, T_map_end, double(b) / kBuckets);
  for (auto& q : scan.points) {
    const int b = std::clamp(static_cast<int>(std::lround(q.t / duration_s * kBuckets)), 0, kBuckets);
    const Eigen::Vector3d v = T[b] * Eigen::Vector3d(q.x, q.y, q.z);
    q.x = static_cast<float>(v.x()), q.y = static_cast<float>(v.y()), q.z = static_cast<float>(v.z());
  }
}

}  // namespace roadslam::odometry
