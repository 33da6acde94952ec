#include "roadslam/registration/point_cloud.h"

#include <roadslam/common/scan.h>

#include <cmath>
#include <unordered_set>

#include "target_impl.h"

namespace roadslam::registration {

PointCloud toPointCloud(const roadslam::Scan& scan) {
  PointCloud out;
  out.reserve(scan.points.size());
  for (const auto& p : scan.points) out.emplace_back(p.x, p.y, p.z);
  return out;
}

PointCloud voxelDownsample(const PointCloud& points, double voxel_m) {
  std::unordered_set<uint64_t, VoxelHash> seen;
  seen.reserve(points.size());
  PointCloud out;
  out.reserve(points.size() / 4 + 16);
  const double inv = 1.0 / voxel_m;
  for (const auto& p : points) {
    if (!p.allFinite()) continue;
    if (seen.insert(voxelKey(p, inv)).second) out.push_back(p);
  }
  return out;
}

}  // namespace roadslam::registration
