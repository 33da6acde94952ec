// Degeneracy along the motion (registration::SurfaceInformation::along) on synthetic scenes whose answer is known:
// a tube (a tunnel: walls, road, ceiling) measures nothing along its axis, a box (the same tube
// closed by end walls) does; and the weakened information keeps what is not weak.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "../../registration/tests/labelled_cloud.h"
#include "roadslam/registration/gaussian_voxel_map.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/odometry/weak_directions.h"

using namespace roadslam::odometry;

namespace {

using roadslam::registration::test::Cloud;

constexpr double kHalfWidth = 5.75, kRoad = -1.9, kCeiling = 3.6;  // [m] about the sensor
constexpr double kHalfLength = 40.0;  // [m]

// A tunnel around the sensor along x (|x| < half_length): walls and road sampled densely, the ceiling
// as a VLP-16 sees it: one ring per upper beam, circles of radius h / tan(elevation) that cross the
// ceiling almost straight across the tube. With \p end_walls the tube is a closed box.
Cloud tube(double half_length, bool end_walls, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.005);
  const auto n = [&] { return Eigen::Vector3d(noise(rng), noise(rng), noise(rng)); };
  Cloud c;
  for (double x = -half_length; x <= half_length; x += 0.2) {
    for (double y = -kHalfWidth + 0.1; y < kHalfWidth; y += 0.2) c.add(Eigen::Vector3d(x, y, kRoad) + n(), true);
    for (double z = kRoad + 0.1; z < kCeiling; z += 0.2) {
      c.add(Eigen::Vector3d(x, kHalfWidth, z) + n(), false);
      c.add(Eigen::Vector3d(x, -kHalfWidth, z) + n(), false);
    }
  }
  for (double e_deg = 3; e_deg <= 15; e_deg += 2) {
    const double R = kCeiling / std::tan(e_deg * M_PI / 180);
    for (double a = 0; a < 2 * M_PI; a += 0.05 / R) {
      const Eigen::Vector3d p(R * std::cos(a), R * std::sin(a), kCeiling);
      if (std::abs(p.y()) < kHalfWidth && std::abs(p.x()) < half_length) c.add(p + n(), false);
    }
  }
  if (end_walls) {
    for (double y = -kHalfWidth + 0.1; y < kHalfWidth; y += 0.2)
      for (double z = kRoad + 0.1; z < kCeiling; z += 0.2) {
        c.add(Eigen::Vector3d(half_length, y, z) + n(), false);
        c.add(Eigen::Vector3d(-half_length, y, z) + n(), false);
      }
  }
  return c;
}

struct Aligned {
  roadslam::registration::RegistrationResult r;
  roadslam::registration::SurfaceInformation surface;
};

Aligned alignTube(bool end_walls) {
  // No cap on the points per voxel: the scene is inserted row by row along x, and a capped voxel
  // would keep a short slice of its row (a corner of wall and road then reads as thin along x).
  roadslam::registration::GaussianVoxelMap map(1.0, 100000, 100.0);
  const Cloud m = tube(kHalfLength, end_walls, 1);
  map.insert(m.points, m.ground);
  // The next sweep from the same place, other noise; in the open tube it ends short of the map's ends
  // (a wall's last column reads as a pole: the end of a tunnel is visible).
  const Cloud s = tube(end_walls ? kHalfLength : kHalfLength - 10, end_walls, 2);
  roadslam::registration::VoxelAlignParams vp;
  vp.max_correspondence_distance_m = 1.0;
  vp.kernel_scale_m = 0.2;
  vp.degeneracy_threshold = Params{}.degeneracy_threshold;
  Aligned a;
  a.r = roadslam::registration::align(map, s.points, Eigen::Isometry3d::Identity(), vp, nullptr, &a.surface);
  return a;
}

}  // namespace

TEST(WeakDirections, TubeMeasuresNothingAlongItsAxisTheBoxDoes) {
  const double threshold = Params{}.motion_degeneracy_threshold;
  const Aligned tunnel = alignTube(false);
  ASSERT_TRUE(tunnel.r.converged);
  std::cout << "information along x per pair: tube " << tunnel.surface.along(Eigen::Vector3d::UnitX()) << "\n";
  EXPECT_LT(tunnel.surface.along(Eigen::Vector3d::UnitX()), 0.1 * threshold);
  EXPECT_GT(tunnel.surface.along(Eigen::Vector3d::UnitY()), 10 * threshold);  // the walls
  EXPECT_GT(tunnel.surface.along(Eigen::Vector3d::UnitZ()), 10 * threshold);  // road and ceiling
  // The ceiling's rings, read as upright surfaces across the tube, give the full Hessian an axis:
  // the reason the motion is judged without them.
  const Eigen::Matrix3d I_tt = tunnel.r.information.topLeftCorner<3, 3>();
  EXPECT_GT(I_tt(0, 0), 0.05 * I_tt(1, 1));

  const Aligned box = alignTube(true);
  ASSERT_TRUE(box.r.converged);
  EXPECT_GT(box.surface.along(Eigen::Vector3d::UnitX()), 3 * threshold);
  // A diagonal motion still has its component along y measured.
  EXPECT_GT(tunnel.surface.along(Eigen::Vector3d(1, 1, 0).normalized()), threshold);
}

TEST(WeakDirections, InformationReducedAlongTheWeakDirectionOnly) {
  Eigen::Matrix<double, 6, 6> A = Eigen::Matrix<double, 6, 6>::Random();
  const Eigen::Matrix<double, 6, 6> info = A * A.transpose() + 100 * Eigen::Matrix<double, 6, 6>::Identity();
  Eigen::Matrix<double, 6, 6> measured = 0.5 * info;
  measured(0, 0) = 1e-3;  // nothing measured along x
  roadslam::registration::Degeneracy none;
  const Eigen::Vector3d n = Eigen::Vector3d::UnitX();
  const WeakBasis W = weakBasis(none, &n);
  ASSERT_EQ(W.cols(), 1);
  const double lever = 10.0;
  const auto out = reduceInformation(info, measured, W, lever);
  EXPECT_NEAR(out(0, 0), 1e-3, 1e-9);                                       // along the weak direction: as measured
  EXPECT_TRUE((out.bottomRightCorner<5, 5>().isApprox(info.bottomRightCorner<5, 5>())));  // elsewhere unchanged
  EXPECT_NEAR(out.row(0).tail<5>().norm(), 0.0, 1e-12);                     // and uncoupled from it
  EXPECT_TRUE(weakBasis(none, nullptr).cols() == 0);
  EXPECT_TRUE(reduceInformation(info, measured, weakBasis(none, nullptr), lever).isApprox(info));
}
