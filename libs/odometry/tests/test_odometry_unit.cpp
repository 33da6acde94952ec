#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include "roadslam/odometry/odometry.h"

using namespace roadslam;
using odometry::FrameStatus;

namespace {

// A street canyon closed by buildings across both ends (so every direction is observable): road,
// two facades with recesses, poles; the sensor 1.9 m above the road.
Scan canyonSweep(double x_offset, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.f, 0.01f);
  Scan s;
  s.stamp_s = 0;
  auto add = [&](double x, double y, double z) {
    ScanPoint p;
    p.x = static_cast<float>(x - x_offset) + noise(rng);
    p.y = static_cast<float>(y) + noise(rng);
    p.z = static_cast<float>(z) + noise(rng);
    s.points.push_back(p);
  };
  for (double x = -40; x <= 40; x += 0.2) {
    for (double y = -8; y <= 8; y += 0.4) add(x, y, -1.9);
    const double recess = std::fmod(std::abs(x), 6.0) < 2.0 ? 0.5 : 0.0;
    for (double z = -1.9; z <= 8; z += 0.3) {
      add(x, 8 + recess, z);
      add(x, -8 - recess, z);
    }
  }
  for (double y = -8; y <= 8; y += 0.2) {
    for (double z = -1.9; z <= 8; z += 0.3) {
      add(-40, y, z);
      add(40, y, z);
    }
  }
  for (double px = -35; px <= 35; px += 10) {
    for (double z = -1.9; z <= 3; z += 0.1) add(px, 6.0, z);
  }
  return s;
}

odometry::Params testParams() {
  odometry::Params p;
  p.preprocess.filters = {"range"};
  p.deskew = false;
  return p;
}

}  // namespace

TEST(OdometryUnit, StandingVehicleHoldsItsPose) {
  odometry::Odometry odo(testParams());
  for (int i = 0; i < 10; ++i) {
    Scan s = canyonSweep(0.0, 100 + i);
    s.stamp_s = 0.1 * i;
    const auto r = odo.process(s);
    EXPECT_LT(r.T_world_lidar.translation().norm(), 0.01) << "frame " << i << ": " << r.T_world_lidar.translation().transpose() << " " << odometry::toString(r.status) << " inl " << r.inliers << "/" << r.points_registered;
    if (i > 0) {
      EXPECT_EQ(r.status, FrameStatus::Standstill) << "frame " << i;
    }
  }
}

TEST(OdometryUnit, FollowsAConstantSpeedDriveThroughTheCanyon) {
  odometry::Odometry odo(testParams());
  for (int i = 0; i < 20; ++i) {
    Scan s = canyonSweep(0.8 * i, 200 + i);  // 8 m/s
    s.stamp_s = 0.1 * i;
    const auto r = odo.process(s);
    ASSERT_NE(r.status, FrameStatus::NotConverged) << r.reason;
    EXPECT_NEAR(r.T_world_lidar.translation().x(), 0.8 * i, 0.05) << "frame " << i;
    EXPECT_NEAR(r.T_world_lidar.translation().y(), 0.0, 0.05) << "frame " << i;
  }
}

TEST(OdometryUnit, ANonFinitePriorIsIgnoredAndSaid) {
  odometry::Odometry odo(testParams());
  for (int i = 0; i < 12; ++i) {
    Scan s = canyonSweep(0.8 * i, 300 + i);  // 8 m/s
    s.stamp_s = 0.1 * i;
    std::optional<odometry::MotionPrior> prior;
    if (i >= 5 && i <= 7) {
      prior = odometry::MotionPrior{};
      prior->T_prev_curr.translation().x() = i == 6 ? std::numeric_limits<double>::infinity() : std::nan("");
      prior->speed_mps = 8.0;
    }
    const auto r = odo.process(s, prior);
    ASSERT_TRUE(r.T_world_lidar.matrix().allFinite()) << "frame " << i;
    EXPECT_NEAR(r.T_world_lidar.translation().x(), 0.8 * i, 0.05) << "frame " << i;
    EXPECT_EQ(r.reason.find("prior not finite") != std::string::npos, prior.has_value()) << "frame " << i << ": " << r.reason;
  }
}

TEST(OdometryUnit, EmptyAndNaNSweepsAreReportedNotFatal) {
  odometry::Odometry odo(testParams());
  Scan first = canyonSweep(0, 1);
  odo.process(first);
  Scan empty;
  empty.stamp_s = 0.1;
  const auto r_empty = odo.process(empty);
  EXPECT_EQ(r_empty.status, FrameStatus::Empty);
  Scan nans;
  nans.stamp_s = 0.2;
  for (int i = 0; i < 1000; ++i) {
    ScanPoint p;
    p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN();
    nans.points.push_back(p);
  }
  const auto r_nan = odo.process(nans);
  EXPECT_EQ(r_nan.status, FrameStatus::Empty);
  EXPECT_TRUE(r_nan.T_world_lidar.matrix().allFinite());
  Scan again = canyonSweep(0, 2);
  again.stamp_s = 0.3;
  const auto r_again = odo.process(again);  // the run goes on
  EXPECT_TRUE(r_again.status == FrameStatus::Ok || r_again.status == FrameStatus::Standstill);
}

TEST(OdometryUnit, ParamsRoundTripAndBadValuesNameTheKey) {
  odometry::Params p;
  p.map_voxel_m = 0.7;
  p.keyframe_angle_rad = 0.2;
  p.matcher = odometry::Matcher::Registration;
  mrpt::config::CConfigFileMemory cfg;
  p.saveToConfigFile(cfg);
  odometry::Params q;
  q.loadFromConfigFile(cfg);
  EXPECT_DOUBLE_EQ(q.map_voxel_m, 0.7);
  EXPECT_NEAR(q.keyframe_angle_rad, 0.2, 1e-8);  // the ini holds degrees with 9 digits
  EXPECT_EQ(q.matcher, odometry::Matcher::Registration);
  mrpt::config::CConfigFileMemory bad(std::string("[odometry]\nmatcher = kiss\n"));
  try {
    q.loadFromConfigFile(bad);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("matcher"), std::string::npos);
  }
}

TEST(OdometryUnit, MapExclusionMovesWithItsVelocity) {
  odometry::MapExclusion b;
  b.stamp_s = 10.0, b.box.centre_m = {10, 0}, b.velocity_world_mps = {5, 0};
  b.box.yaw_rad = M_PI / 2, b.box.length_m = 4.0, b.box.width_m = 2.0, b.box.z_min_m = -2, b.box.z_max_m = 0;
  EXPECT_TRUE(b.contains({10.9, 1.9, -1}, 10.0));    // the length axis along y
  EXPECT_FALSE(b.contains({11.1, 0, -1}, 10.0));
  EXPECT_TRUE(b.contains({15.9, 0, -1}, 11.0));      // 5 m further 1 s later
  EXPECT_FALSE(b.contains({10.0, 0, -1}, 11.0));
  EXPECT_FALSE(b.contains({15.0, 0, 0.5}, 11.0));    // above it
}

// A car driving beside the vehicle through the canyon: boxes on it keep its points out of the local
// map and nothing else; the pose is as good as without them.
TEST(OdometryUnit, ExcludedBoxesKeepACarsPointsOutOfTheMap) {
  auto sweepWithCar = [](int i) {
    Scan s = canyonSweep(0.8 * i, 300 + i);
    for (double x = -2; x <= 2; x += 0.1)  // its side, 3 m left, at 12 m/s: x = 5 + 1.2 i in the world
      for (double z = -1.5; z <= -0.5; z += 0.1) {
        ScanPoint p;
        p.x = static_cast<float>(5 + 1.2 * i + x - 0.8 * i), p.y = 3.f, p.z = static_cast<float>(z);
        s.points.push_back(p);
      }
    s.stamp_s = 0.1 * i;
    return s;
  };
  odometry::MapExclusion car;
  car.box.centre_m = {5, 3}, car.velocity_world_mps = {12, 0};
  car.box.length_m = 4.6, car.box.width_m = 1.0, car.box.z_min_m = -1.7, car.box.z_max_m = -0.3;
  odometry::MapExclusion elsewhere = car;
  elsewhere.box.centre_m = {5, -3};
  for (const auto& boxes : {std::vector<odometry::MapExclusion>{car}, std::vector<odometry::MapExclusion>{elsewhere}}) {
    odometry::Odometry odo(testParams());
    odo.setMapExclusions(boxes);
    int excluded = 0;
    for (int i = 0; i < 10; ++i) {
      const auto r = odo.process(sweepWithCar(i));
      ASSERT_NE(r.status, FrameStatus::NotConverged) << r.reason;
      EXPECT_NEAR(r.T_world_lidar.translation().x(), 0.8 * i, 0.05) << "frame " << i;
      excluded += r.map_points_excluded;
      if (boxes.front().box.centre_m.y() > 0) {
        EXPECT_GT(r.map_points_excluded, 20) << "frame " << i;  // the car's side, one point per 0.25 m voxel
      }
    }
    if (boxes.front().box.centre_m.y() < 0) {
      EXPECT_EQ(excluded, 0) << "a box where nothing stands keeps nothing out";
    }
  }
}

// The same car, seen for 1 s before anything labelled it: its voxels are in the local map. A box on
// it with erase_back_s = 1 s erases the voxels it swept over that second and nothing else.
TEST(OdometryUnit, ExclusionBoxesEraseWhatTheCarLeftBeforeItsLabel) {
  odometry::Odometry odo(testParams());
  for (int i = 0; i < 10; ++i) {
    Scan s = canyonSweep(0.8 * i, 300 + i);
    for (double x = -2; x <= 2; x += 0.1)
      for (double z = -1.5; z <= -0.5; z += 0.1) {
        ScanPoint p;
        p.x = static_cast<float>(5 + 1.2 * i + x - 0.8 * i), p.y = 3.f, p.z = static_cast<float>(z);
        s.points.push_back(p);
      }
    s.stamp_s = 0.1 * i;
    ASSERT_NE(odo.process(s).status, FrameStatus::NotConverged);
  }
  auto onPath = [](const Eigen::Vector3d& m) { return std::abs(m.y() - 3) < 0.6 && m.z() > -1.7 && m.z() < -0.3 && m.x() > 2 && m.x() < 19; };
  auto count = [&](bool path) {
    int n = 0;
    for (const auto& m : odo.matcher().mapPoints()) n += onPath(m) == path;
    return n;
  };
  const int car_before = count(true), rest_before = count(false);
  ASSERT_GT(car_before, 5);
  odometry::MapExclusion car;
  car.stamp_s = 0.9, car.box.centre_m = {5 + 1.2 * 9, 3}, car.velocity_world_mps = {12, 0};
  car.box.length_m = 2 * (2.3 + 0.3), car.box.width_m = 2 * (0.9 + 0.3), car.box.z_min_m = -1.8, car.box.z_max_m = -0.2;
  odometry::MapExclusion no_erase = car;
  no_erase.erase_back_s = 0;
  EXPECT_EQ(odo.setMapExclusions({no_erase}), 0u);  // 0 s: its current box only keeps new points out
  EXPECT_EQ(count(true), car_before);
  car.erase_back_s = 1.0;
  EXPECT_GE(odo.setMapExclusions({car}), static_cast<size_t>(car_before));  // and voxels too thin for a mean
  EXPECT_EQ(count(true), 0);
  EXPECT_EQ(count(false), rest_before);
}
