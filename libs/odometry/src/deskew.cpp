#include "roadslam/odometry/deskew.h"

#include <cmath>

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

}  // namespace roadslam::odometry
