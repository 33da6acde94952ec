// Boundary metrics on hand-made ground truth: straight curbs, known offsets, a missing side.
#include <gtest/gtest.h>

#include <cmath>
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
