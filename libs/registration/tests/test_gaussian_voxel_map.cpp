#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "labelled_cloud.h"
#include "roadslam/registration/gaussian_voxel_map.h"

using namespace roadslam::registration;

namespace {

using test::Cloud;

// A yard closed by three walls (x = 12, y = +-8) on a flat road 1.9 m below the sensor. The walls
// carry single scan rings at the heights given, each in its own 1 m voxel row, as a VLP-16 sees a
// facade 10-20 m away; the road is sampled densely.
Cloud yard(const std::vector<double>& ring_heights_m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.005);
  const auto n = [&] { return Eigen::Vector3d(noise(rng), noise(rng), noise(rng)); };
  Cloud c;
  for (double x = -10; x <= 11.5; x += 0.25)
    for (double y = -7.5; y <= 7.5; y += 0.25) c.add(Eigen::Vector3d(x, y, -1.9) + n(), true);
  for (double z : ring_heights_m) {
    for (double s = -7.9; s <= 7.9; s += 0.05) c.add(Eigen::Vector3d(12, s, z) + n(), false);
    for (double s = -9.9; s <= 11.9; s += 0.05) {
      c.add(Eigen::Vector3d(s, 8, z) + n(), false);
      c.add(Eigen::Vector3d(s, -8, z) + n(), false);
    }
  }
  return c;
}

Eigen::Isometry3d yardMotion() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(1.5 * M_PI / 180, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(0.3 * M_PI / 180, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.25, -0.15, 0.05);
  return T;
}

RegistrationResult alignYard(bool ring_lines_on_walls) {
  GaussianVoxelMap map(1.0, 100, 100.0, 7, ring_lines_on_walls);
  const Cloud m = yard({0.3, 1.8, 3.3}, 1);
  map.insert(m.points, m.ground);
  // The next sweep's rings cross the walls at other heights: the sensor has moved.
  const Eigen::Isometry3d T_map_lidar = yardMotion();
  Cloud s = yard({0.8, 2.3}, 2);
  for (auto& p : s.points) p = T_map_lidar.inverse() * p;
  VoxelAlignParams vp;
  vp.max_correspondence_distance_m = 1.5;
  vp.kernel_scale_m = 0.5;
  return align(map, s.points, Eigen::Isometry3d::Identity(), vp);
}

}  // namespace

TEST(GaussianVoxelMap, OneRingOnAWallConstrainsAcrossTheWallOnly) {
  // One horizontal ring across a wall whose normal is x, inside one voxel.
  Cloud c;
  for (double y = 0.05; y < 0.95; y += 0.05) c.add(Eigen::Vector3d(12.5, y, 1.4), false);
  GaussianVoxelMap walls(1.0, 50, 100.0, 7, true);
  walls.insert(c.points, c.ground);
  const auto* v = walls.nearest(Eigen::Vector3d(12.6, 0.5, 1.4), 1.0);
  ASSERT_NE(v, nullptr);
  EXPECT_NEAR(v->info(0, 0), 1.0, 1e-6);
  EXPECT_NEAR(v->info.trace(), 1.0, 1e-6);  // a projector on one direction: across the wall

  GaussianVoxelMap waiting(1.0, 50, 100.0, 7, false);
  waiting.insert(c.points, c.ground);
  EXPECT_EQ(waiting.nearest(Eigen::Vector3d(12.6, 0.5, 1.4), 1.0), nullptr);

  // The same ring on the road constrains height only.
  std::vector<uint8_t> road(c.points.size(), 1);
  GaussianVoxelMap ground(1.0, 50, 100.0, 7, true);
  ground.insert(c.points, road);
  const auto* g = ground.nearest(Eigen::Vector3d(12.5, 0.5, 1.5), 1.0);
  ASSERT_NE(g, nullptr);
  EXPECT_NEAR(g->info(2, 2), 1.0, 1e-6);
  EXPECT_NEAR(g->info.trace(), 1.0, 1e-6);
}

TEST(GaussianVoxelMap, SingleRingsOnWallsRecoverTheMotionTheyCross) {
  // Oracle: the known motion between map and sweep. Every horizontal constraint comes from
  // single rings, and the sweep's rings lie at other heights than the map's.
  const auto r = alignYard(true);
  ASSERT_TRUE(r.converged) << r.reason;
  const Eigen::Isometry3d E = yardMotion().inverse() * r.T_target_source;
  EXPECT_LT(E.translation().norm(), 0.01);
  EXPECT_LT(Eigen::AngleAxisd(E.linear()).angle() * 180 / M_PI, 0.05);
  EXPECT_EQ(r.degeneracy.num_weak, 0);
}

TEST(GaussianVoxelMap, WithoutRingLinesTheYardIsOnlyARoad) {
  // The same sweep while single rings wait for a second one: only the road constrains, and the
  // alignment says that x, y and yaw are not observed.
  const auto r = alignYard(false);
  EXPECT_GE(r.degeneracy.num_weak, 3);
}
