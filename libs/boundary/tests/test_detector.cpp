// Detector on analytic sweeps: curb lines, obstacles, free space and the reasons of bad input.
#include <gtest/gtest.h>

#include <mrpt/img/CImage.h>

#include <cmath>
#include <filesystem>

#include "roadslam/boundary/detector.h"
#include "roadslam/boundary/output.h"
#include "synthetic_road.h"

using namespace roadslam::boundary;
using roadslam::boundary::test::Box;
using roadslam::boundary::test::Road;
using roadslam::boundary::test::castSweep;

namespace {

Params defaults() {
  Params p;
  p.ground.sensor_height_m = 1.9;
  return p;
}

/// Max |y_est - y_true| over the reported polyline within the band.
double maxLateralError(const SideBoundary& s, double y_true) {
  double e = 0;
  for (const auto& v : s.polyline_vehicle) e = std::max(e, std::abs(v.y - y_true));
  return e;
}

}  // namespace

TEST(Detector, StraightCurbsFoundAtTheirLines) {
  Road road;
  BoundaryDetector det(defaults());
  const auto f = det.process(castSweep(road), Eigen::Isometry3d::Identity(), 0.0);
  ASSERT_TRUE(f.left.found) << f.left.reason;
  ASSERT_TRUE(f.right.found) << f.right.reason;
  EXPECT_LT(maxLateralError(f.left, 4.0), 0.10);
  EXPECT_LT(maxLateralError(f.right, -3.5), 0.10);
  EXPECT_GE(f.left.polyline_vehicle.front().x, 5.0 - 1e-9);
  EXPECT_GT(f.left.confidence, 0.1);
  EXPECT_EQ(f.status, FrameStatus::Ok);
}

TEST(Detector, ParkedCarIsAnObstacleNotABoundary) {
  Road road;
  road.boxes.push_back({8, 12.5, -3.3, -1.5, -1.9, -0.4});  // car in the parking lane, right
  BoundaryDetector det(defaults());
  const auto f = det.process(castSweep(road), Eigen::Isometry3d::Identity(), 0.0);
  ASSERT_TRUE(f.right.found) << f.right.reason;
  EXPECT_LT(maxLateralError(f.right, -3.5), 0.15);
  bool car = false;
  for (const auto& o : f.obstacles) {
    if (!(std::abs(o.center.x - 10.25) < 1.0 && std::abs(o.center.y + 2.4) < 1.0)) continue;
    car = true;
    // one cluster (the objects segmentation): the car's side facing the road (y = -1.5 m, x 8-12.5 m;
    // the cast sweep's rings find its rear face too low for an obstacle), its L-shape box along the road
    EXPECT_NEAR(o.center.x, 10.25, 0.3);
    EXPECT_NEAR(o.center.y, -1.5, 0.15);
    EXPECT_NEAR(o.length_m, 4.5, 0.4);
    EXPECT_LT(o.width_m, 0.3);
    EXPECT_LT(std::abs(o.yaw_rad), 2.0 * M_PI / 180.0);
  }
  EXPECT_TRUE(car) << "no obstacle at the parked car";
  // Free space ahead stops at the car's face, not beyond.
  double free_ahead_right = 1e9;
  for (const auto& v : f.free_space) {
    if (std::abs(std::atan2(v.y, v.x) - std::atan2(-2.0, 8.0)) < 0.02) free_ahead_right = std::hypot(v.x, v.y);
  }
  EXPECT_LT(free_ahead_right, 9.0);
}

TEST(Detector, OpenSquareSaysNoCurbs) {
  Road road;
  road.left_y.reset();
  road.right_y.reset();
  BoundaryDetector det(defaults());
  const auto f = det.process(castSweep(road), Eigen::Isometry3d::Identity(), 0.0);
  EXPECT_FALSE(f.left.found);
  EXPECT_FALSE(f.right.found);
  EXPECT_NE(f.left.reason.find("too few curb points"), std::string::npos) << f.left.reason;
  EXPECT_EQ(f.curb_count, 0u);
}

TEST(Detector, SweepFullOfVehiclesSaysWhichSideAndWhy) {
  Road road;
  for (double x = -20; x < 40; x += 5.0) {
    road.boxes.push_back({x, x + 4.5, 1.5, 3.3, -1.9, -0.4});    // a row of cars left
    road.boxes.push_back({x, x + 4.5, -3.3, -1.5, -1.9, -0.4});  // and right
  }
  BoundaryDetector det(defaults());
  const auto f = det.process(castSweep(road), Eigen::Isometry3d::Identity(), 0.0);
  for (const SideBoundary* s : {&f.left, &f.right}) {
    EXPECT_FALSE(s->reason.empty());
    if (s->found) {
      EXPECT_EQ(s->reason, "ok");
    }
  }
  EXPECT_GE(f.obstacles.size(), 10u);
}

TEST(Detector, NoGroundAndNoPointsAreReported) {
  BoundaryDetector det(defaults());
  const auto empty = det.process(roadslam::Scan{}, Eigen::Isometry3d::Identity(), 0.0);
  EXPECT_EQ(empty.status, FrameStatus::NoPoints);
  EXPECT_EQ(empty.left.reason, "no points in the sweep");
  Road road;
  road.sensor_height = 8.0;  // the detector expects 1.9 m: nothing near its ground
  road.left_y.reset();
  road.right_y.reset();
  const auto f = det.process(castSweep(road), Eigen::Isometry3d::Identity(), 0.1);
  EXPECT_EQ(f.status, FrameStatus::NoGround);
  EXPECT_NE(f.right.reason.find("no ground"), std::string::npos);
}

TEST(Detector, MemoryFollowsTheVehicle) {
  // Two sweeps 2 m apart: the curb points of the first, moved by the pose, agree with the second.
  Road road;
  BoundaryDetector det(defaults());
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  det.process(castSweep(road, 1), T, 0.0);
  T.translation().x() = 2.0;  // the road is invariant along x: same sweep 2 m further
  const auto f = det.process(castSweep(road, 2), T, 0.1);
  ASSERT_TRUE(f.left.found);
  EXPECT_LT(maxLateralError(f.left, 4.0), 0.10);
  ASSERT_FALSE(f.left.polyline_map.empty());
  EXPECT_NEAR(f.left.polyline_map.front().x, f.left.polyline_vehicle.front().x + 2.0, 1e-6);
}

TEST(Detector, ThesisBaselineRunsAndExplains) {
  Params p = defaults();
  p.method = Method::Thesis;
  Road road;
  BoundaryDetector det(p);
  const auto f = det.process(castSweep(road), Eigen::Isometry3d::Identity(), 0.0);
  for (const SideBoundary* s : {&f.left, &f.right}) EXPECT_FALSE(s->reason.empty());
}

TEST(Detector, CostGridMarksFreeAndObstacleCells) {
  Road road;
  road.boxes.push_back({10, 14.5, -0.9, 0.9, -1.9, -0.4});  // car ahead in our lane
  BoundaryDetector det(defaults());
  const auto f = det.process(castSweep(road), Eigen::Isometry3d::Identity(), 0.0);
  const auto& g = f.grid;
  auto at = [&](double x, double y) {
    return g.cost[static_cast<size_t>(std::floor((y - g.y0_m) / g.resolution_m)) * g.nx +
                  static_cast<size_t>(std::floor((x - g.x0_m) / g.resolution_m))];
  };
  EXPECT_EQ(at(6.0, 0.0), CostGrid::kFree);
  EXPECT_EQ(at(20.0, 0.0), CostGrid::kUnknown);  // hidden behind the car
  bool obstacle = false;
  for (double y = -0.9; y <= 0.9; y += 0.1) obstacle = obstacle || at(10.05, y) == CostGrid::kObstacle;
  EXPECT_TRUE(obstacle);
}

TEST(Detector, LocalMapShowsACurbTheSweepCannotSee) {
  // A row of cars in the left lane hides the left curb from this sweep; the local map (points of
  // earlier sweeps, map frame) still holds it.
  Road hidden;
  for (double x = -10; x < 40; x += 4.6) hidden.boxes.push_back({x, x + 4.5, 1.5, 3.3, -1.9, -0.4});
  Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
  T_map_lidar.translation() = Eigen::Vector3d(100, 50, 0);
  const auto clear = castSweep(Road{}, 3);
  std::vector<Eigen::Vector3f> map;
  for (const auto& q : clear.points) map.push_back((T_map_lidar * Eigen::Vector3d(q.x, q.y, q.z)).cast<float>());

  BoundaryDetector alone(defaults());
  const auto a = alone.process(castSweep(hidden), T_map_lidar, 0.0);
  EXPECT_FALSE(a.left.found) << "the cars should hide the left curb";
  BoundaryDetector with_map(defaults());
  const auto b = with_map.process(castSweep(hidden), T_map_lidar, 0.0, &map);
  ASSERT_TRUE(b.left.found) << b.left.reason;
  EXPECT_LT(maxLateralError(b.left, 4.0), 0.10);
  // Obstacles come from the sweep: the cars are found either way.
  auto cars = [](const BoundaryFrame& f) {
    int n = 0;
    for (const auto& o : f.obstacles) n += o.center.y > 1.3 && o.center.y < 3.5 && o.center.x > 0;
    return n;
  };
  EXPECT_GE(cars(a), 2);  // cars 0.1 m apart merge into longer clusters
  EXPECT_EQ(cars(a), cars(b));
}

TEST(Detector, CostGridPngHoldsTheCosts) {
  Road road;
  road.boxes.push_back({10, 14.5, -0.9, 0.9, -1.9, -0.4});
  BoundaryDetector det(defaults());
  const auto f = det.process(castSweep(road), Eigen::Isometry3d::Identity(), 0.0);
  const std::string path = std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_cost_test.png";
  std::filesystem::create_directories(std::string(ROADSLAM_BINARY_DIR) + "/test_data");
  writeCostGridPng(path, f.grid);
  mrpt::img::CImage img;
  ASSERT_TRUE(img.loadFromFile(path, 0));
  ASSERT_EQ(static_cast<int>(img.getWidth()), f.grid.nx);
  ASSERT_EQ(static_cast<int>(img.getHeight()), f.grid.ny);
  size_t diff = 0;
  for (int j = 0; j < f.grid.ny; ++j)
    for (int i = 0; i < f.grid.nx; ++i)
      diff += img.at<uint8_t>(i, f.grid.ny - 1 - j) != f.grid.cost[static_cast<size_t>(j) * f.grid.nx + i];
  EXPECT_EQ(diff, 0u);
}
