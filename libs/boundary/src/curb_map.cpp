#include "roadslam/boundary/curb_map.h"

#include <algorithm>

#include "internal.h"

namespace roadslam::boundary {

void CurbMap::insert(const std::vector<Eigen::Vector3d>& pts_map, size_t frame) {
  for (const auto& m : pts_map) {
    Cell& c = cells_[detail::cellKey(m.x(), m.y(), cell_m_)];
    c.sum += m, ++c.points;
    if (c.sightings == 0 || c.last_frame != frame) ++c.sightings;
    c.last_frame = frame;
  }
}

size_t CurbMap::erase(const std::vector<Eigen::Vector3d>& tall_map, int radius_cells) {
  if (radius_cells < 0 || cells_.empty()) return 0;
  size_t n = 0;
  for (const auto& m : tall_map)
    for (int dx = -radius_cells; dx <= radius_cells; ++dx)
      for (int dy = -radius_cells; dy <= radius_cells; ++dy)
        n += cells_.erase(detail::cellKey(m.x() + dx * cell_m_, m.y() + dy * cell_m_, cell_m_));
  return n;
}

void CurbMap::prune(const Eigen::Isometry3d& T_map_lidar, double keep_behind_m, double keep_radius_m, size_t frame,
                    size_t max_age_frames) {
  const Eigen::Isometry3d T_lidar_map = T_map_lidar.inverse();
  for (auto it = cells_.begin(); it != cells_.end();) {
    const Eigen::Vector3d v = T_lidar_map * (it->second.sum / it->second.points);
    const bool drop = v.x() < -keep_behind_m || v.head<2>().norm() > keep_radius_m ||
                      frame - it->second.last_frame > max_age_frames;
    it = drop ? cells_.erase(it) : std::next(it);
  }
}

std::vector<Vec2> CurbMap::inVehicle(const Eigen::Isometry3d& T_map_lidar, int min_sightings, double max_range_m) const {
  const Eigen::Isometry3d T_lidar_map = T_map_lidar.inverse();
  const Eigen::Vector2d at = T_map_lidar.translation().head<2>();
  const double r2 = max_range_m * max_range_m;
  std::vector<Vec2> out;
  out.reserve(std::min<size_t>(cells_.size(), 100000));
  for (const auto& [key, c] : cells_) {
    if (c.sightings < min_sightings) continue;
    const Eigen::Vector3d m = c.sum / c.points;
    if ((m.head<2>() - at).squaredNorm() > r2) continue;
    const Eigen::Vector3d v = T_lidar_map * m;
    out.push_back({v.x(), v.y()});
  }
  return out;
}

}  // namespace roadslam::boundary
