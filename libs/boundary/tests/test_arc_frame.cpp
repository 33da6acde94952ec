// The arc frame of the side fits: an oracle in closed form (a circle concentric with the vehicle's
// path is d = const, s = radius-scaled angle) and round trips.
#include <gtest/gtest.h>

#include <Eigen/Dense>

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

namespace {

using roadslam::boundary::detail::BendFrame;

/// Curb cells every 0.2 m of a road whose reference path has curvature k0 up to arc length sb, then
/// k1 (closed form: the frame's own toXY is not used), at offsets \p d (left +); vehicle frame.
std::vector<Vec2> bentCurbs(double k0, double sb, double k1, std::vector<double> d, double s_max = 45) {
  std::vector<Vec2> out;
  for (double off : d) {
    for (double s = -8; s <= s_max; s += 0.2) {
      auto arcXY = [](double k, double s, double dd) {
        if (std::abs(k) < 1e-9) return Vec2{s, dd};
        return Vec2{(1 / k - dd) * std::sin(k * s), 1 / k - (1 / k - dd) * std::cos(k * s)};
      };
      if (s <= sb) {
        out.push_back(arcXY(k0, s, off));
        continue;
      }
      const Vec2 P = arcXY(k0, sb, 0), l = arcXY(k1, s - sb, off);
      const double h = k0 * sb;
      out.push_back({P.x + std::cos(h) * l.x - std::sin(h) * l.y, P.y + std::sin(h) * l.x + std::cos(h) * l.y});
    }
  }
  return out;
}

}  // namespace

TEST(BendFrame, CurbsOfAStraightThenABendAreConstantOffsets) {
  const BendFrame f{ArcFrame{0.0}, 8.0, ArcFrame{1.0 / 14}};
  std::mt19937 rng(5);
  for (double d : {4.0, -3.5}) {
    const auto cells = bentCurbs(0.0, 8.0, 1.0 / 14, {d}, 30);
    for (const auto& q : cells) {
      Vec2 a;
      ASSERT_TRUE(f.toArc(q, a)) << q.x << " " << q.y;
      EXPECT_NEAR(a.y, d, 1e-9);
      const Vec2 b = f.toXY(a);  // and back
      EXPECT_NEAR(b.x, q.x, 1e-9);
      EXPECT_NEAR(b.y, q.y, 1e-9);
    }
  }
}

// The bend is chosen from the curb cells ahead alone: a left corner entry 8 m ahead (radius 14 m),
// a right one, and a corner exit (the vehicle turning at 1/14, straight from 10 m on) are found
// near their true s_bend and curvature; on a straight road the path's frame stays.
TEST(BendFrame, ChosenFromTheCurbsAhead) {
  roadslam::boundary::Params p;
  struct Case {
    double k0, sb, k1;
  };
  for (const Case c : {Case{0.0, 8.0, 1.0 / 14}, Case{0.0, 12.0, -1.0 / 14}, Case{1.0 / 14, 10.0, 0.0}}) {
    const auto cells = bentCurbs(c.k0, c.sb, c.k1, {4.0, -3.5});
    int votes[2];
    const BendFrame f = roadslam::boundary::detail::chooseFrame(cells, c.k0, p, votes);
    ASSERT_TRUE(f.bent()) << c.sb << " " << c.k1;
    EXPECT_NEAR(f.s_bend, c.sb, 1.01) << c.k1;
    EXPECT_NEAR(f.b.kappa, c.k1, 0.011) << c.sb;
    EXPECT_GE(votes[0], votes[1] + p.bend_margin_bins);
    // In the chosen frame each curb is what the side fit models (d quadratic in s) within centimetres
    // over the band, though the grid leaves the curvature up to 0.0033 1/m off.
    for (double d : {4.0, -3.5}) {
      std::vector<Vec2> sd;
      for (const auto& q : bentCurbs(c.k0, c.sb, c.k1, {d})) {
        Vec2 a;
        if (q.x >= 0 && f.toArc(q, a) && a.x <= p.band_max_x_m) sd.push_back(a);
      }
      ASSERT_GT(sd.size(), 100u);
      Eigen::MatrixXd A(sd.size(), 3);
      Eigen::VectorXd b(sd.size());
      for (size_t i = 0; i < sd.size(); ++i) A.row(i) << 1, sd[i].x, sd[i].x * sd[i].x, b(i) = sd[i].y;
      const Eigen::VectorXd r = A * A.colPivHouseholderQr().solve(b) - b;
      EXPECT_LT(r.cwiseAbs().maxCoeff(), 0.10) << c.sb << " " << c.k1 << " d " << d << ": chose " << f.s_bend << " " << f.b.kappa;
    }
  }
  const auto straight = bentCurbs(0.0, 1e9, 0.0, {4.0, -3.5});
  EXPECT_FALSE(roadslam::boundary::detail::chooseFrame(straight, 0.0, p).bent());
  p.bend_max_curvature = 0;  // off: always the path's frame
  EXPECT_FALSE(roadslam::boundary::detail::chooseFrame(bentCurbs(0.0, 8.0, 1.0 / 14, {4.0, -3.5}), 0.0, p).bent());
}

// The road ends at the first curb: cells of a curb at y = 4 m seen over 25 m and of a sidewalk's far
// edge 3 m beyond it seen over 48 m (more bins) give the curb; cells of a parked car's sill 1 m inside
// the curb (nearer than a sidewalk's width) do not replace it.
TEST(SideFit, TheFirstCurbFromTheVehicleBeatsASidewalksFarEdge) {
  roadslam::boundary::Params p;
  std::mt19937 noise(11);
  std::normal_distribution<double> n(0.0, 0.03);
  auto line = [&](double y, double x0, double x1) {
    std::vector<Vec2> v;
    for (double x = x0; x <= x1; x += 0.2) v.push_back({x, y + n(noise)});
    return v;
  };
  auto fit = [&](std::vector<Vec2> a, const std::vector<Vec2>& b) {
    a.insert(a.end(), b.begin(), b.end());
    std::mt19937 rng(7);
    return roadslam::boundary::detail::fitSide(a, +1, p, rng);
  };
  const auto curb = line(4.0, -5, 20), far_edge = line(7.0, -10, 38);
  auto s = fit(curb, far_edge);
  ASSERT_TRUE(s.found) << s.reason;
  EXPECT_NEAR(s.coeffs[0], 4.0, 0.1);
  p.inner_curb_share = 0;  // off: the far edge's bins win, as before
  s = fit(curb, far_edge);
  ASSERT_TRUE(s.found) << s.reason;
  EXPECT_NEAR(s.coeffs[0], 7.0, 0.1);
  p.inner_curb_share = 0.5;
  s = fit(line(3.0, 0, 12), line(4.0, -10, 38));  // a sill 1 m inside the curb
  ASSERT_TRUE(s.found) << s.reason;
  EXPECT_NEAR(s.coeffs[0], 4.0, 0.1);
}

// The whole-drive mode's frame along the drive's own path: a drive straight along +x, then a left
// quarter circle of radius R round (20, R), then straight along +y, sampled at 10 Hz at 5 m/s (map
// frame). A curb at offset d from the path is the closed-form oracle: s = arc length, d = offset.
TEST(PathFrame, CurbAlongAnLShapedDriveIsConstantOffset) {
  using roadslam::boundary::detail::pathAround;
  const double R = 14.0, L = R * M_PI / 2;
  auto pathPoint = [&](double u, double d) {  // point at arc length u of the path, d to its left
    if (u < 20) return Eigen::Vector3d(u, d, 0.0);
    if (u < 20 + L) {
      const double th = (u - 20) / R;
      return Eigen::Vector3d(20 + (R - d) * std::sin(th), R - (R - d) * std::cos(th), 0.0);
    }
    return Eigen::Vector3d(20 + R - d, R + (u - 20 - L), 0.0);
  };
  std::vector<Eigen::Vector3d> drive;
  for (double u = 0; u < 80; u += 0.5) drive.push_back(pathPoint(u, 0));
  const size_t k = 20;  // the vehicle at u = 10 m, heading +x, lifted 1.9 m above the path
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = pathPoint(10, 0) + Eigen::Vector3d(0, 0, 1.9);
  const auto f = pathAround(drive, k, T, 10.0, 40.0, 1.0);
  ASSERT_GE(f.v.size(), 40u);
  EXPECT_NEAR(f.s.front(), -10.0, 1.0);
  EXPECT_GE(f.s.back(), 40.0);
  for (double d : {3.95, -3.95, 7.45, -7.45}) {
    for (double u = 2; u <= 48; u += 1.5) {
      const Eigen::Vector3d m = pathPoint(u, d);
      const Eigen::Vector3d v = T.inverse() * m;
      Vec2 a;
      ASSERT_TRUE(f.toArc({v.x(), v.y()}, a));
      // The polyline's 1.5 m chords stand off the arc by 1.5^2 / (8 R) = 2 cm; arc lengths shrink by
      // the chords' R (1 - sinc) < 0.1 %. Where the curvature jumps (u = 20 m, 20 m + L) the vertex
      // normal is half turned, so s there is off by up to |d| a / 4 (a = 0.11 rad per chord).
      const bool jump = std::abs(u - 20) < 1.6 || std::abs(u - 20 - L) < 1.6;
      EXPECT_NEAR(a.y, d, 0.02) << "u = " << u << ", d = " << d;
      EXPECT_NEAR(a.x, u - 10, jump ? 0.05 * std::abs(d) : 0.05) << "u = " << u << ", d = " << d;
      const Vec2 back = f.toXY(a);
      EXPECT_NEAR(back.x, v.x(), 1e-6);
      EXPECT_NEAR(back.y, v.y(), 1e-6);
    }
  }
  // Past the first and last vertices the path goes on straight.
  Vec2 a;
  ASSERT_TRUE(f.toArc({-30.0, -3.0}, a));
  EXPECT_NEAR(a.x, -30.0, 1e-6);
  EXPECT_NEAR(a.y, -3.0, 1e-6);
}
