#include "roadslam/common/oriented_box.h"

#include <cmath>

namespace roadslam {

bool OrientedBox::contains(const Eigen::Vector3d& p, double margin_m) const {
  // p in the box's axes: along its length (c, s) and across it (-s, c)
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad), dx = p.x() - centre_m.x(), dy = p.y() - centre_m.y();
  return std::abs(c * dx + s * dy) <= 0.5 * length_m + margin_m && std::abs(-s * dx + c * dy) <= 0.5 * width_m + margin_m &&
         p.z() >= z_min_m - margin_m && p.z() <= z_max_m + margin_m;
}

OrientedBox OrientedBox::grown(double margin_m) const {
  // 0.5 * (length + 2 margin) == 0.5 length + margin exactly (halving is exact in binary floating
  // point): contains() of the grown box answers as contains() with the margin
  OrientedBox b = *this;
  b.length_m += 2 * margin_m, b.width_m += 2 * margin_m;
  b.z_min_m -= margin_m, b.z_max_m += margin_m;
  return b;
}

std::array<Eigen::Vector2d, 4> OrientedBox::corners() const {
  const Eigen::Vector2d u(std::cos(yaw_rad), std::sin(yaw_rad)), v(-u.y(), u.x());  // front, left
  const double hl = 0.5 * length_m, hw = 0.5 * width_m;
  return {centre_m + hl * u + hw * v, centre_m + hl * u - hw * v, centre_m - hl * u - hw * v, centre_m - hl * u + hw * v};
}

OrientedBox OrientedBox::placed(const Eigen::Isometry3d& T_to_from) const {
  const double dyaw = std::atan2(T_to_from(1, 0), T_to_from(0, 0)), z0 = T_to_from.translation().z();
  OrientedBox b = *this;
  b.centre_m = (T_to_from * Eigen::Vector3d(centre_m.x(), centre_m.y(), 0)).head<2>();
  b.yaw_rad = std::atan2(std::sin(yaw_rad + dyaw), std::cos(yaw_rad + dyaw));
  b.z_min_m = z_min_m + z0, b.z_max_m = z_max_m + z0;
  return b;
}

}  // namespace roadslam
