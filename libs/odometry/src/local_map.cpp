#include "roadslam/odometry/local_map.h"

#include <cmath>

namespace roadslam::odometry {

LocalMap::LocalMap(double voxel_m, int max_points_per_voxel, double radius_m)
    : voxel_m_(voxel_m), radius_m_(radius_m), max_per_voxel_(max_points_per_voxel) {}

void LocalMap::insert(const std::vector<Eigen::Vector3d>& points_world) {
  for (const auto& p : points_world) {
    const Eigen::Vector3i k = (p / voxel_m_).array().floor().cast<int>();
    auto& v = voxels_[k];
    if (static_cast<int>(v.size()) >= max_per_voxel_) continue;
    if (v.empty()) v.reserve(max_per_voxel_);
    v.push_back(p);
    ++num_points_;
  }
}

void LocalMap::removeFar(const Eigen::Vector3d& origin_world) {
  const double r2 = radius_m_ * radius_m_;
  for (auto it = voxels_.begin(); it != voxels_.end();) {
    if ((it->second.front() - origin_world).squaredNorm() > r2) {
      num_points_ -= it->second.size();
      it = voxels_.erase(it);
    } else {
      ++it;
    }
  }
}

std::vector<Eigen::Vector3d> LocalMap::points() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(num_points_);
  for (const auto& [k, v] : voxels_) out.insert(out.end(), v.begin(), v.end());
  return out;
}

void LocalMap::clear() {
  voxels_.clear();
  num_points_ = 0;
}

}  // namespace roadslam::odometry
