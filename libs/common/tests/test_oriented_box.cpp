// OrientedBox against hand-computed boxes: an axis-aligned one (exact), one turned by 90 deg and one
// turned by atan2(3, 4) (cos 0.8, sin 0.6, so its corners and axes are short decimals).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "roadslam/common/oriented_box.h"

using roadslam::OrientedBox;

namespace {

OrientedBox box(double cx, double cy, double yaw, double length, double width, double z_min, double z_max) {
  OrientedBox b;
  b.centre_m = {cx, cy}, b.yaw_rad = yaw, b.length_m = length, b.width_m = width, b.z_min_m = z_min, b.z_max_m = z_max;
  return b;
}

void expectCorners(const OrientedBox& b, const double (&xy)[4][2]) {
  const auto c = b.corners();
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(c[k].x(), xy[k][0], 1e-12) << "corner " << k;
    EXPECT_NEAR(c[k].y(), xy[k][1], 1e-12) << "corner " << k;
  }
}

}  // namespace

TEST(OrientedBox, CornersAreFrontLeftFrontRightRearRightRearLeft) {
  expectCorners(box(0, 0, 0, 4, 2, 0, 1), {{2, 1}, {2, -1}, {-2, -1}, {-2, 1}});
  // turned to face +y: its front is up, its left towards -x
  expectCorners(box(10, 5, M_PI / 2, 4, 2, 0, 1), {{9, 7}, {11, 7}, {11, 3}, {9, 3}});
  // axes (0.8, 0.6) and (-0.6, 0.8), half extents 5 and 2 about (1, 2)
  expectCorners(box(1, 2, std::atan2(3.0, 4.0), 10, 4, 0, 1), {{3.8, 6.6}, {6.2, 3.4}, {-1.8, -2.6}, {-4.2, 0.6}});
}

TEST(OrientedBox, APointOnAFaceIsInsideAndJustBeyondIsNot) {
  const OrientedBox b = box(0, 0, 0, 4, 2, -1, 1);
  EXPECT_TRUE(b.contains({0, 0, 0}));
  EXPECT_TRUE(b.contains({2, 0, 0}));    // front face
  EXPECT_TRUE(b.contains({-2, -1, 1}));  // rear right top corner
  EXPECT_TRUE(b.contains({0, 0, -1}));   // floor
  EXPECT_FALSE(b.contains({2 + 1e-9, 0, 0}));
  EXPECT_FALSE(b.contains({0, -1 - 1e-9, 0}));
  EXPECT_FALSE(b.contains({0, 0, 1 + 1e-9}));
  EXPECT_FALSE(b.contains({0, 0, -1 - 1e-9}));
}

TEST(OrientedBox, ATurnedBoxHoldsWhatLiesAlongItsOwnAxes) {
  const OrientedBox b = box(1, 2, std::atan2(3.0, 4.0), 10, 4, 0, 2);
  // (along, across) = (4.9, 0), (5.1, 0), (0, 1.9), (0, -2.1) in the box's axes
  EXPECT_TRUE(b.contains({1 + 0.8 * 4.9, 2 + 0.6 * 4.9, 1}));
  EXPECT_FALSE(b.contains({1 + 0.8 * 5.1, 2 + 0.6 * 5.1, 1}));
  EXPECT_TRUE(b.contains({1 - 0.6 * 1.9, 2 + 0.8 * 1.9, 1}));
  EXPECT_FALSE(b.contains({1 + 0.6 * 2.1, 2 - 0.8 * 2.1, 1}));
  // 4.5 m along x from the centre: inside the box unturned, but 2.7 m across the turned one's axis
  EXPECT_FALSE(b.contains({5.5, 2, 1}));
  EXPECT_TRUE(box(1, 2, 0, 10, 4, 0, 2).contains({5.5, 2, 1}));
}

TEST(OrientedBox, GrownByAMarginOnEverySide) {
  const OrientedBox b = box(0, 0, 0, 4, 2, 0, 1), g = b.grown(0.5);
  EXPECT_EQ(g.centre_m, b.centre_m);
  EXPECT_EQ(g.yaw_rad, 0);
  EXPECT_EQ(g.length_m, 5);
  EXPECT_EQ(g.width_m, 3);
  EXPECT_EQ(g.z_min_m, -0.5);
  EXPECT_EQ(g.z_max_m, 1.5);
  EXPECT_TRUE(b.contains({2.5, -1.5, -0.5}, 0.5));  // the grown box's corner
  EXPECT_FALSE(b.contains({2.5 + 1e-9, 0, 0}, 0.5));
  const OrientedBox s = b.grown(-0.5);  // shrunk
  EXPECT_EQ(s.length_m, 3);
  EXPECT_FALSE(s.contains({1.6, 0, 0.5}));
}

// contains() with a margin and contains() of the grown box are one test, to the last bit: unturned
// boxes at the origin (a point's coordinates are then its offsets along the axes, exactly), with points
// on each face's last double inside and the first outside.
TEST(OrientedBox, AMarginAndTheGrownBoxAgreeToTheLastBit) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 1000; ++i) {
    const OrientedBox b = box(0, 0, 0, 3 + 2 * u(rng), 1.6 + 0.4 * u(rng), -1.9 + 0.2 * u(rng), -0.4 + 0.2 * u(rng));
    const double margin = 0.2 + 0.2 * u(rng);
    const OrientedBox g = b.grown(margin);
    const double faces[4] = {0.5 * b.length_m + margin, 0.5 * b.width_m + margin, b.z_min_m - margin, b.z_max_m + margin};
    for (int axis = 0; axis < 4; ++axis) {
      const double at = faces[axis], out = std::nextafter(at, axis == 2 ? -1e9 : 1e9);
      for (double q : {at, out}) {
        Eigen::Vector3d p(0, 0, -1);
        p[axis < 2 ? axis : 2] = q;
        EXPECT_EQ(b.contains(p, margin), q == at) << "box " << i << " face " << axis;
        EXPECT_EQ(g.contains(p), q == at) << "box " << i << " face " << axis;
      }
    }
  }
}

// A lidar-frame box placed in the map by a pose turned 90 deg and raised 2 m: the centre through the
// pose, the yaw turned by 90 deg and wrapped, the heights raised, the extents kept.
TEST(OrientedBox, PlacedThroughALevelPose) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(10, 5, 2);
  const OrientedBox p = box(1, 0, 0.2, 4, 2, -1.5, 0).placed(T);
  EXPECT_NEAR(p.centre_m.x(), 10, 1e-12);
  EXPECT_NEAR(p.centre_m.y(), 6, 1e-12);
  EXPECT_NEAR(p.yaw_rad, 0.2 + M_PI / 2, 1e-12);
  EXPECT_EQ(p.length_m, 4);
  EXPECT_EQ(p.width_m, 2);
  EXPECT_EQ(p.z_min_m, 0.5);
  EXPECT_EQ(p.z_max_m, 2);
  // 3.0 + pi/2 is past pi: wrapped to 3.0 + pi/2 - 2 pi
  EXPECT_NEAR(box(0, 0, 3.0, 4, 2, 0, 1).placed(T).yaw_rad, 3.0 + M_PI / 2 - 2 * M_PI, 1e-12);
}
