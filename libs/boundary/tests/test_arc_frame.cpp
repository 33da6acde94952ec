// The arc frame of the side fits: an oracle in closed form (a circle concentric with the vehicle's
// path is d = const, s = radius-scaled angle) and round trips.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../src/internal.h"
#include "roadslam/boundary/detector.h"
#include "synthetic_road.h"

using roadslam::boundary::Vec2;
using roadslam::boundary::detail::ArcFrame;

TEST(ArcFrame, ConcentricCurbIsConstantOffset) {
  for (double R : {13.75, -13.75, 40.0}) {  // left turn, right turn, gentle bend [m]
    const ArcFrame arc{1.0 / R};
    for (double d : {3.95, -3.95, 7.45}) {  // curb offsets left (+) / right (-) of the path [m]
      for (double th = -0.5; th <= 1.5; th += 0.25) {  // angle round the centre of curvature (0, R) [rad]
        const double sg = R > 0 ? 1.0 : -1.0;
        const Vec2 q{(R - d) * std::sin(sg * th), R - (R - d) * std::cos(sg * th)};
        Vec2 a;
        ASSERT_TRUE(arc.toArc(q, a)) << R << " " << d << " " << th;
        EXPECT_NEAR(a.y, d, 1e-9);
        EXPECT_NEAR(a.x, std::abs(R) * th, 1e-9);  // arc length along the path
      }
    }
  }
}

TEST(ArcFrame, RoundTripAndStraight) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-15, 30);
  const ArcFrame arc{1.0 / 20.0}, flat{0.0};
  int kept = 0;
  for (int i = 0; i < 1000; ++i) {
    const Vec2 q{u(rng), u(rng) / 2};
    Vec2 a, f;
    ASSERT_TRUE(flat.toArc(q, f));
    EXPECT_DOUBLE_EQ(f.x, q.x);
    EXPECT_DOUBLE_EQ(f.y, q.y);
    if (!arc.toArc(q, a)) continue;  // beyond the usable part of the arc
    ++kept;
    const Vec2 b = arc.toXY(a);
    EXPECT_NEAR(b.x, q.x, 1e-9);
    EXPECT_NEAR(b.y, q.y, 1e-9);
  }
  EXPECT_GT(kept, 900);
  Vec2 a;
  EXPECT_FALSE(arc.toArc({0.0, 35.0}, a)) << "across the centre of curvature the map is ambiguous";
}

// The detector's arc frame is the driven path's: poses along a circle of radius 14 m (left turn),
// 1 m apart, give kappa = 1/14 once 5 sweeps of path are known; a right turn the opposite sign.
TEST(ArcFrame, DetectorTakesTheDrivenPathsCurvature) {
  const auto sweep = roadslam::boundary::test::castSweep(roadslam::boundary::test::Road{});
  for (double R : {14.0, -14.0}) {
    roadslam::boundary::Params p;
    p.ground.sensor_height_m = 1.9;
    roadslam::boundary::BoundaryDetector det(p);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    double kappa = 0;
    for (int i = 0; i < 8; ++i) {
      // Exact chord of 1 m along the circle, then the heading of the tangent there.
      const double dth = 2 * std::asin(0.5 / std::abs(R)) * (R > 0 ? 1 : -1);
      T.translation() += T.linear() * Eigen::Vector3d(std::cos(dth / 2), std::sin(dth / 2), 0);
      T.rotate(Eigen::AngleAxisd(dth, Eigen::Vector3d::UnitZ()));
      kappa = det.process(sweep, T, 0.1 * i).path_curvature;
      if (i == 0) {
        EXPECT_EQ(kappa, 0.0) << "one pose: no path yet";
      }
    }
    EXPECT_NEAR(kappa, 1.0 / R, 0.002) << R;  // heading change over 5 chords / their length
  }
}
