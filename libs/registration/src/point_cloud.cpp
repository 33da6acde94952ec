#include "roadslam/registration/point_cloud.h"

#include <roadslam/common/scan.h>

#include <cmath>

#include "ndt_grid.h"

namespace roadslam::registration {

PointCloud toPointCloud(const roadslam::Scan& scan) {
  PointCloud out;
  out.reserve(scan.points.size());
  for (const auto& p : scan.points) out.emplace_back(p.x, p.y, p.z);
  return out;
}

PointCloud voxelDownsample(const PointCloud& points, double voxel_m) {
  FlatIndex seen(points.size() / 4 + 16);
  PointCloud out;
  out.reserve(points.size() / 4 + 16);
  const double inv = 1.0 / voxel_m;
  for (const auto& p : points) {
    if (!p.allFinite()) continue;
    bool inserted = false;
    seen.findOrInsert(voxelKey(p, inv), inserted);
    if (inserted) out.push_back(p);
  }
  return out;
}

}  // namespace roadslam::registration
