// Boundary metrics on hand-made ground truth: straight curbs, known offsets, a missing side.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <nlohmann/json.hpp>

#include "roadslam/eval/boundary_metrics.h"

using namespace roadslam::eval;

namespace {

// Road along world x: curbs at y = +4 and y = -3.5; the vehicle drives along x at y = 0, heading
// rotated by yaw so vehicle and world frames differ.
std::vector<std::vector<Eigen::Vector3d>> curbs() {
  std::vector<Eigen::Vector3d> l, r;
  for (double x = -50; x <= 200; x += 2) l.emplace_back(x, 4.0, 0.0), r.emplace_back(x, -3.5, 0.0);
  return {l, r};
}

roadslam::datasets::Trajectory drive(int n) {
  roadslam::datasets::Trajectory t;
  for (int i = 0; i < n; ++i) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(i * 1.0, 0, 1.9);
    t.poses.push_back(T);
    t.stamps_s.push_back(10.0 + 0.1 * i);
  }
  return t;
}

nlohmann::json side(bool found, double y, double x0, double x1, double dx_world) {
  nlohmann::json pl = nlohmann::json::array();
  for (double x = x0; x <= x1; x += 1.0) pl.push_back({x + dx_world, y});
  return {{"found", found}, {"polyline_map", pl}};
}

}  // namespace

TEST(BoundaryMetrics, LateralAtPicksTheNearestCrossingOnEachSide) {
  std::vector<std::vector<Eigen::Vector2d>> pl = {{{0, 3}, {10, 5}}, {{0, 8}, {10, 8}}, {{0, -2}, {10, -2}}};
  EXPECT_NEAR(lateralAt(pl, 5, +1, 15), 4.0, 1e-12);
  EXPECT_NEAR(lateralAt(pl, 5, -1, 15), -2.0, 1e-12);
  EXPECT_TRUE(std::isnan(lateralAt(pl, 12, +1, 15)));
  EXPECT_TRUE(std::isnan(lateralAt(pl, 5, +1, 2.5)));
}

TEST(BoundaryMetrics, OffsetEstimateGivesThatError) {
  const auto gt = drive(20);
  std::vector<nlohmann::json> est;
  for (int i = 0; i < 20; ++i) {
    nlohmann::json f;
    f["stamp_s"] = 10.0 + 0.1 * i;
    f["left"] = side(true, 4.05, 5, 30, i * 1.0);      // 5 cm off
    f["right"] = side(i % 4 != 0, -3.5 - 0.2, 5, 30, i * 1.0);  // 20 cm off, missing every 4th
    est.push_back(f);
  }
  const auto m = evaluateBoundaries(curbs(), gt, est);
  EXPECT_EQ(m.frames_scored, 20);
  EXPECT_DOUBLE_EQ(m.left_detection_rate, 1.0);
  EXPECT_DOUBLE_EQ(m.right_detection_rate, 0.75);
  EXPECT_DOUBLE_EQ(m.detection_rate, 0.75);
  // 26 stations per side: left 20 frames x 0.05, right 15 frames x 0.2
  EXPECT_NEAR(m.lateral_error_mean_m, (20 * 0.05 + 15 * 0.2) / 35.0, 1e-9);
  EXPECT_NEAR(m.lateral_error_p95_m, 0.2, 1e-9);
  // Per frame (roadslam-eval bounds --frames-csv): the same offsets, frame by frame.
  ASSERT_EQ(m.per_frame.size(), 20u);
  for (int i = 0; i < 20; ++i) {
    const auto& f = m.per_frame[static_cast<size_t>(i)];
    EXPECT_TRUE(f.scored);
    EXPECT_TRUE(f.found[0]);
    EXPECT_EQ(f.found[1], i % 4 != 0) << i;
    EXPECT_EQ(f.gt_stations[0], 26);
    EXPECT_NEAR(f.error_mean_m[0], 0.05, 1e-9);
    EXPECT_NEAR(f.error_max_m[1], i % 4 != 0 ? 0.2 : 0.0, 1e-9);
  }
  const std::string csv = perFrameCsv(m);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 21);
}

TEST(BoundaryMetrics, ShortEstimateIsNotADetection) {
  const auto gt = drive(3);
  std::vector<nlohmann::json> est;
  for (int i = 0; i < 3; ++i) {
    nlohmann::json f;
    f["stamp_s"] = 10.0 + 0.1 * i;
    f["left"] = side(true, 4.0, 5, 10, i * 1.0);  // covers 6 of 26 stations
    f["right"] = side(true, -3.5, 5, 30, i * 1.0);
    est.push_back(f);
  }
  est.push_back({{"stamp_s", 10.3}, {"status", "no_pose"}});
  const auto m = evaluateBoundaries(curbs(), gt, est);
  EXPECT_EQ(m.frames, 4);
  EXPECT_EQ(m.frames_scored, 3);
  EXPECT_DOUBLE_EQ(m.left_detection_rate, 0.0);
  EXPECT_DOUBLE_EQ(m.right_detection_rate, 1.0);
  EXPECT_NEAR(m.lateral_error_mean_m, 0.0, 1e-9);
}

// A 90 deg left corner of radius 12 m (lane centre), curbs at 12 - 4 = 8 m (inner, left) and
// 12 + 3.5 = 15.5 m (outer, right): along the path both sides keep their offsets; on the vehicle's
// axis, entering the corner, the axis leaves the road and the outer curb crosses it as "left".
namespace {
Eigen::Vector2d arc(double r, double a) { return {r * std::sin(a), 12.0 - r * std::cos(a)}; }

std::vector<std::vector<Eigen::Vector3d>> cornerCurbs() {
  std::vector<Eigen::Vector3d> l, r;
  for (double x = -60; x < 0; x += 1) l.emplace_back(x, 4.0, 0.0), r.emplace_back(x, -3.5, 0.0);
  for (double a = 0; a <= M_PI / 2 + 1e-9; a += M_PI / 90) {
    const Eigen::Vector2d pl = arc(8.0, a), pr = arc(15.5, a);
    l.emplace_back(pl.x(), pl.y(), 0.0), r.emplace_back(pr.x(), pr.y(), 0.0);
  }
  for (double y = 13; y < 80; y += 1) l.emplace_back(4.0, y, 0.0), r.emplace_back(15.5, y, 0.0);
  return {l, r};
}

roadslam::datasets::Trajectory cornerDrive() {
  roadslam::datasets::Trajectory t;
  auto add = [&](const Eigen::Vector2d& p, double yaw) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(p.x(), p.y(), 1.9);
    t.stamps_s.push_back(10.0 + 0.1 * static_cast<double>(t.poses.size()));
    t.poses.push_back(T);
  };
  for (double x = -40; x < 0; x += 1) add({x, 0}, 0);
  for (double a = 0; a < M_PI / 2; a += 1.0 / 12.0) add(arc(12, a), a);
  for (double y = 12; y < 60; y += 1) add({12, y}, M_PI / 2);
  return t;
}

nlohmann::json polyline(const std::vector<Eigen::Vector3d>& l, double offset_towards_centre) {
  nlohmann::json pl = nlohmann::json::array();
  for (size_t i = 0; i < l.size(); ++i) {
    const Eigen::Vector3d& a = l[i == 0 ? 0 : i - 1];
    const Eigen::Vector3d& b = l[i == 0 ? 1 : i];
    const Eigen::Vector2d u = (b - a).head<2>().normalized(), n(-u.y(), u.x());
    const Eigen::Vector2d q = l[i].head<2>() + offset_towards_centre * n;
    pl.push_back({q.x(), q.y()});
  }
  return pl;
}
}  // namespace

TEST(BoundaryMetrics, PathStationsFollowACornerAxisStationsDoNot) {
  const auto curbs = cornerCurbs();
  const auto gt = cornerDrive();
  std::vector<nlohmann::json> est;
  for (size_t i = 0; i < gt.poses.size(); ++i) {
    nlohmann::json f;
    f["stamp_s"] = gt.stamps_s[i];
    f["left"] = {{"found", true}, {"polyline_map", polyline(curbs[0], -0.1)}};   // 0.1 m towards the road
    f["right"] = {{"found", true}, {"polyline_map", polyline(curbs[1], +0.1)}};
    est.push_back(f);
  }
  BoundaryEvalParams along;
  along.stations = "path";
  const auto path = evaluateBoundaries(curbs, gt, est, along);
  EXPECT_EQ(path.frames_scored, static_cast<int>(gt.poses.size()));
  EXPECT_DOUBLE_EQ(path.detection_rate, 1.0);
  EXPECT_NEAR(path.lateral_error_mean_m, 0.1, 0.01);
  EXPECT_LT(path.lateral_error_max_m, 0.15);
  BoundaryEvalParams axis;
  axis.stations = "axis";
  const auto ax = evaluateBoundaries(curbs, gt, est, axis);
  // the same (correct) estimate, read on the axis: the corner frames pair curbs of different sides
  EXPECT_GT(ax.lateral_error_max_m, 1.0);
  EXPECT_THROW(
      [&] {
        BoundaryEvalParams bad;
        bad.stations = "diagonal";
        evaluateBoundaries(curbs, gt, est, bad);
      }(),
      std::invalid_argument);
}

// An estimate written in its own map frame (an odometry run: origin at the first sweep, rotated) and
// carrying its T_map_lidar scores as the same estimate in the GT world; read with the GT pose it is
// off the road.
TEST(BoundaryMetrics, EstimateReadInItsOwnMapFrame) {
  const auto gt = drive(20);
  Eigen::Isometry3d T_odo_world = Eigen::Isometry3d::Identity();
  T_odo_world.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_odo_world.translation() = Eigen::Vector3d(-5, 2, -1.9);
  std::vector<nlohmann::json> world, odo;
  for (int i = 0; i < 20; ++i) {
    nlohmann::json f;
    f["stamp_s"] = gt.stamps_s[static_cast<size_t>(i)];
    f["left"] = side(true, 4.05, 4, 31, i * 1.0);  // past the band: no station on a rounded end vertex
    f["right"] = side(true, -3.6, 4, 31, i * 1.0);
    world.push_back(f);
    nlohmann::json g = f;
    const Eigen::Isometry3d T = T_odo_world * gt.poses[static_cast<size_t>(i)];
    g["T_map_lidar"] = nlohmann::json::array();
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) g["T_map_lidar"].push_back(T.matrix()(r, c));
    for (const char* s : {"left", "right"}) {
      for (auto& q : g[s]["polyline_map"]) {
        const Eigen::Vector3d p = T_odo_world * Eigen::Vector3d(q[0].get<double>(), q[1].get<double>(), 0.0);
        q = {p.x(), p.y(), p.z()};
      }
    }
    odo.push_back(g);
  }
  const auto a = evaluateBoundaries(curbs(), gt, world), b = evaluateBoundaries(curbs(), gt, odo);
  EXPECT_DOUBLE_EQ(a.detection_rate, 1.0);
  EXPECT_DOUBLE_EQ(b.detection_rate, 1.0);
  EXPECT_EQ(b.stations, a.stations);
  EXPECT_NEAR(b.lateral_error_mean_m, a.lateral_error_mean_m, 1e-9);
  EXPECT_NEAR(a.lateral_error_mean_m, 0.075, 1e-9);
  BoundaryEvalParams gt_frame;
  gt_frame.est_in_gt_frame = true;
  EXPECT_LT(evaluateBoundaries(curbs(), gt, odo, gt_frame).detection_rate, 0.5);
}

// The per-frame CSV keeps an epoch stamp's microseconds (10 significant digits had cut it to 0.1 s).
TEST(BoundaryMetrics, PerFrameCsvKeepsEpochStampMicroseconds) {
  BoundaryMetrics m;
  BoundaryFrameScore f;
  f.stamp_s = 1700000000.123456;
  m.per_frame.push_back(f);
  const std::string csv = perFrameCsv(m);
  const auto row = csv.substr(csv.find('\n') + 1);
  EXPECT_NEAR(std::stod(row.substr(0, row.find(','))), f.stamp_s, 1e-6) << row;
}
