#include <gtest/gtest.h>
#include <roadslam/common/scan.h>
#include <roadslam/registration/point_cloud.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <tuple>

namespace roadslam::registration {
namespace {

// Reference: first point per voxel found with an ordered map of floor(p / voxel).
PointCloud referenceVoxel(const PointCloud& pts, double v) {
  std::map<std::tuple<long, long, long>, bool> seen;
  PointCloud out;
  for (const auto& p : pts) {
    if (!p.allFinite()) continue;
    const auto k = std::make_tuple(static_cast<long>(std::floor(p.x() / v)), static_cast<long>(std::floor(p.y() / v)),
                                   static_cast<long>(std::floor(p.z() / v)));
    if (seen.emplace(k, true).second) out.push_back(p);
  }
  return out;
}

TEST(VoxelDownsample, MatchesReferenceFirstPointPerVoxel) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  PointCloud pts;
  for (int i = 0; i < 20000; ++i) pts.emplace_back(u(rng), u(rng), 0.1 * u(rng));
  pts[5] = Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  for (double v : {0.25, 0.5, 1.0, 3.0}) {
    const PointCloud got = voxelDownsample(pts, v);
    const PointCloud want = referenceVoxel(pts, v);
    ASSERT_EQ(got.size(), want.size()) << "voxel " << v;
    for (size_t i = 0; i < got.size(); ++i) EXPECT_EQ(got[i], want[i]) << "voxel " << v << " point " << i;
  }
}

TEST(ToPointCloud, KeepsEveryPointInOrder) {
  Scan s;
  s.points.resize(3);
  s.points[1].x = 1.5f;
  s.points[1].y = -2.0f;
  s.points[1].z = 0.25f;
  s.points[2].x = std::numeric_limits<float>::quiet_NaN();
  const PointCloud pc = toPointCloud(s);
  ASSERT_EQ(pc.size(), 3u);
  EXPECT_EQ(pc[1], Eigen::Vector3d(1.5, -2.0, 0.25));
  EXPECT_TRUE(std::isnan(pc[2].x()));
}

}  // namespace
}  // namespace roadslam::registration
