// Every shipped scenario loads and builds; drives obey their limits; the urban loop closes.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <filesystem>

#include "roadslam/sim/simulator.h"
#include "sim_test_util.h"

using namespace roadslam::sim;

namespace {
using roadslam::sim::test::iniPath;
}  // namespace

TEST(Scenarios, EveryShippedIniLoadsAndBuilds) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(iniPath(""))) {
    if (e.path().extension() != ".ini") continue;
    SCOPED_TRACE(e.path().string());
    const ScenarioParams p = ScenarioParams::fromFile(e.path().string());
    EXPECT_EQ(p.name + ".ini", e.path().filename().string());
    const Simulator sim(p);
    EXPECT_GT(sim.world().prisms.size(), 50u);
    EXPECT_GT(sim.trajectory().distance_m(), 200.0);
    EXPECT_GT(sim.duration_s(), 20.0);
    ++n;
  }
  EXPECT_EQ(n, 9);
}

TEST(Scenarios, UnknownKeysAndBadValuesAreNamed) {
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("world", "lenght_m", 3.0);
  ScenarioParams p;
  try {
    p.loadFromConfigFile(cfg);
    FAIL() << "typo accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("lenght_m"), std::string::npos) << e.what();
  }
  mrpt::config::CConfigFileMemory bad;
  bad.write("lidar", "rotation_hz", 30.0);
  EXPECT_THROW(p.loadFromConfigFile(bad), std::runtime_error);
}

TEST(Scenarios, SavedParametersReloadIdentically) {
  ScenarioParams a = ScenarioParams::fromFile(iniPath("hills.ini"));
  mrpt::config::CConfigFileMemory cfg;
  a.saveToConfigFile(cfg);
  ScenarioParams b;
  b.loadFromConfigFile(cfg);
  mrpt::config::CConfigFileMemory cfg2;
  b.saveToConfigFile(cfg2);
  EXPECT_EQ(cfg.getContent(), cfg2.getContent());
  EXPECT_DOUBLE_EQ(b.world.hill_amplitude_m, 6.0);
}

TEST(Scenarios, UrbanLoopReturnsToItsStart) {
  const Simulator sim(ScenarioParams::fromFile(iniPath("urban-loop.ini")));
  const auto& st = sim.trajectory().states();
  const VehicleState& a = st.front();
  const VehicleState& b = st.back();
  EXPECT_LT(std::hypot(b.x - a.x, b.y - a.y), 3.0);
  EXPECT_NEAR(std::remainder(b.yaw - a.yaw, 2 * M_PI), 0.0, 0.05);
  EXPECT_NEAR(sim.trajectory().distance_m(), 1000.0, 60.0);  // 2 (300 + 200) minus the corners
  EXPECT_EQ(a.speed_mps, 0.0);
  EXPECT_EQ(b.speed_mps, 0.0);
}

// Limits of the speed profile, checked by differentiating the 10 ms table (an independent route
// to speed, acceleration and lateral acceleration).
TEST(Scenarios, DrivesRespectTheirLimits) {
  for (const char* name : {"urban-loop.ini", "highway.ini", "parking-lot.ini"}) {
    SCOPED_TRACE(name);
    const ScenarioParams p = ScenarioParams::fromFile(iniPath(name));
    const Simulator sim(p);
    const auto& st = sim.trajectory().states();
    double vmax = 0;
    for (std::size_t i = 1; i + 1 < st.size(); ++i) {
      const double v = std::hypot(st[i + 1].x - st[i - 1].x, st[i + 1].y - st[i - 1].y) / 0.02;
      vmax = std::max(vmax, v);
      ASSERT_LE(v, p.trajectory.max_speed_mps() + 0.05) << "t " << st[i].t_s;
      ASSERT_NEAR(st[i].speed_mps, v, 0.05) << "t " << st[i].t_s;
      const double dyaw = std::remainder(st[i + 1].yaw - st[i - 1].yaw, 2 * M_PI) / 0.02;
      ASSERT_LE(std::abs(dyaw * v), p.trajectory.lateral_accel_mps2 * 1.15 + 0.05) << "t " << st[i].t_s;
    }
    EXPECT_NEAR(vmax, p.trajectory.max_speed_mps(), 0.1 * p.trajectory.max_speed_mps());
  }
}

TEST(Scenarios, SameSeedSameWorldOtherSeedOtherWorld) {
  ScenarioParams p = ScenarioParams::fromFile(iniPath("urban-loop.ini"));
  const Simulator a(p), b(p);
  ASSERT_EQ(a.world().prisms.size(), b.world().prisms.size());
  for (std::size_t i = 0; i < a.world().prisms.size(); ++i) ASSERT_EQ(a.world().prisms[i].cx, b.world().prisms[i].cx);
  p.seed = 99;
  const Simulator c(p);
  bool differs = c.world().prisms.size() != a.world().prisms.size();
  for (std::size_t i = 0; !differs && i < a.world().prisms.size(); ++i) differs = a.world().prisms[i].cx != c.world().prisms[i].cx;
  EXPECT_TRUE(differs);
}

// Traffic never drives through the sensor: moving cars keep to their lanes (oncoming or the next
// lane), so no car footprint (grown by 0.5 m) ever contains the lidar (checked every 0.1 s).
TEST(Scenarios, MovingCarsNeverDriveThroughTheSensor) {
  for (const auto& e : std::filesystem::directory_iterator(iniPath(""))) {
    if (e.path().extension() != ".ini") continue;
    SCOPED_TRACE(e.path().string());
    const Simulator sim(ScenarioParams::fromFile(e.path().string()));
    int inside = 0;
    for (double t = 0; t < sim.trajectory().duration_s(); t += 0.1) {
      const Pose3 T = sim.lidar().lidarPose(t);
      for (const MovingCar& c : sim.world().cars) {
        const Prism q = sim.world().carPrism(c, t);
        const double dx = T.t.x - q.cx, dy = T.t.y - q.cy;
        const double u = std::cos(q.yaw) * dx + std::sin(q.yaw) * dy, v = -std::sin(q.yaw) * dx + std::cos(q.yaw) * dy;
        inside += std::abs(u) <= q.hu + 0.5 && std::abs(v) <= q.hv + 0.5;
      }
    }
    EXPECT_EQ(inside, 0);
  }
}

// Visibility ground truth (gt_objects.json `returns`): the returns the simulator counts on each moving
// car per 0.1 s sample equal an independent count over the true returns (TrueReturn): the points
// within 5 cm of the car's prism at their firing time, fired within 0.05 s of the sample.
TEST(Scenarios, CarReturnsCountThePointsOnEachCar) {
  auto p = ScenarioParams::fromFile(iniPath("urban-loop.ini"));
  p.duration_s = 2.0;
  Simulator sim(p);
  struct Null : PacketSink {
    void packet(double, uint16_t, const uint8_t*, std::size_t) override {}
  } sink;
  std::vector<TrueReturn> truth;
  sim.run(sink, &truth);
  const auto& counted = sim.lidar().carReturns();
  ASSERT_EQ(counted.size(), sim.world().cars.size());
  size_t total = 0, agree = 0, max_per_sample = 0;
  for (std::size_t c = 0; c < sim.world().cars.size(); ++c) {
    std::vector<uint32_t> oracle(21, 0);
    for (const TrueReturn& r : truth) {
      const Prism q = sim.world().carPrism(sim.world().cars[c], r.t_s);
      const double dx = r.p_world.x - q.cx, dy = r.p_world.y - q.cy;
      const double u = std::cos(q.yaw) * dx + std::sin(q.yaw) * dy, v = -std::sin(q.yaw) * dx + std::cos(q.yaw) * dy;
      const double zb = q.zb + q.su * u + q.sv * v, zt = q.zt + q.su * u + q.sv * v;
      if (std::abs(u) > q.hu + 0.05 || std::abs(v) > q.hv + 0.05 || r.p_world.z < zb - 0.05 || r.p_world.z > zt + 0.05) continue;
      const auto k = static_cast<std::size_t>(std::llround(r.t_s / LidarSimulator::kCarSample_s));
      if (k < oracle.size()) ++oracle[k];
    }
    for (std::size_t k = 0; k < oracle.size(); ++k) {
      const uint32_t n = k < counted[c].size() ? counted[c][k] : 0;
      total += oracle[k];
      agree += std::min(oracle[k], n);
      max_per_sample = std::max<size_t>(max_per_sample, n);
      EXPECT_NEAR(double(n), double(oracle[k]), 0.01 * oracle[k] + 2) << "car " << c << " sample " << k;
    }
  }
  EXPECT_GT(max_per_sample, 50u);  // some car is close and seen
  EXPECT_GE(agree, 0.99 * total);
}

// A second drive of the same streets: traffic_seed redraws the moving cars alone (the static
// world stays, prism for prism), start_offset_m starts (and ends) the drive that far along the closed
// route, in the same direction, on the same route points.
TEST(Scenarios, TrafficSeedAndStartOffsetMakeASecondDriveOfTheSameStreets) {
  ScenarioParams p = ScenarioParams::fromFile(iniPath("urban-loop.ini"));
  const Simulator a(p);
  p.world.traffic_seed = 7;
  p.trajectory.start_offset_m = 250;
  const Simulator b(p);
  ASSERT_EQ(a.world().prisms.size(), b.world().prisms.size());
  for (std::size_t i = 0; i < a.world().prisms.size(); ++i) ASSERT_EQ(a.world().prisms[i].cx, b.world().prisms[i].cx);
  ASSERT_EQ(a.world().cars.size(), b.world().cars.size());
  int moved = 0;
  for (std::size_t i = 0; i < a.world().cars.size(); ++i) moved += a.world().cars[i].s0_m != b.world().cars[i].s0_m;
  EXPECT_EQ(moved, static_cast<int>(a.world().cars.size()));
  // the start: the original route's point 250 m along (within the 0.5 m route spacing), same heading
  Vec2 q;
  double heading = 0;
  pointAtArcLength(a.route(), 250, q, heading);
  const VehicleState& s0 = b.trajectory().states().front();
  EXPECT_LT(std::hypot(s0.x - q.x, s0.y - q.y), 0.5);
  EXPECT_NEAR(std::remainder(s0.yaw - heading, 2 * M_PI), 0.0, 0.05);
  EXPECT_NEAR(b.trajectory().distance_m(), a.trajectory().distance_m(), 1.0);  // one whole lap still
  const VehicleState& s1 = b.trajectory().states().back();
  EXPECT_LT(std::hypot(s1.x - q.x, s1.y - q.y), 3.0);
  // an open route has no other start
  ScenarioParams h = ScenarioParams::fromFile(iniPath("highway.ini"));
  h.trajectory.start_offset_m = 10;
  try {
    const Simulator s(h);
    FAIL() << "start_offset_m accepted on an open route";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("start_offset_m"), std::string::npos) << e.what();
  }
}

// Planned traffic (World::planTraffic, followed: World::followTraffic): on the urban loop's 10 m corners every car keeps its lateral
// acceleration v * yaw rate within the limit (central differences of carPose over 1 s, every 0.05 s for
// 80 s; 15 % for the fillets' yaw steps) and reaches its own speed on the straights; unplanned, the
// same cars take the corners at full speed, far beyond it.
TEST(Scenarios, PlannedTrafficSlowsForCornersWithinTheLateralLimit) {
  auto p = ScenarioParams::fromFile(iniPath("urban-loop.ini"));
  auto lateralAndSpeed = [](const World& w, const MovingCar& c, double& max_lat, double& max_v) {
    max_lat = max_v = 0;
    const double dt = 0.5;  // the yaw steps at the fillets' 0.5 m vertices: a 1 s window spans about ten
    for (double t = dt; t < 80; t += 0.05) {
      const CarPose a = w.carPose(c, t - dt), b = w.carPose(c, t), d = w.carPose(c, t + dt);
      const double v = std::hypot(d.x - a.x, d.y - a.y) / (2 * dt);
      const double yaw_rate = std::remainder(d.yaw - a.yaw, 2 * M_PI) / (2 * dt);
      if (std::hypot(d.x - b.x, d.y - b.y) > 20) continue;  // an open road's wrap
      max_lat = std::max(max_lat, std::abs(v * yaw_rate));
      max_v = std::max(max_v, v);
    }
  };
  p.world.moving_car_lateral_accel_mps2 = 2.5;
  const Simulator planned(p);
  ASSERT_FALSE(planned.world().cars.empty());
  for (const MovingCar& c : planned.world().cars) {
    EXPECT_FALSE(c.follow_u.empty());  // and following one another (World::followTraffic)
    double lat = 0, v = 0;
    lateralAndSpeed(planned.world(), c, lat, v);
    EXPECT_LE(lat, 2.5 * 1.15);
    EXPECT_NEAR(v, std::abs(c.speed_mps), 0.02 * std::abs(c.speed_mps));
  }
  p.world.moving_car_lateral_accel_mps2 = 0;
  const Simulator unplanned(p);
  double worst = 0;
  for (const MovingCar& c : unplanned.world().cars) {
    double lat = 0, v = 0;
    lateralAndSpeed(unplanned.world(), c, lat, v);
    worst = std::max(worst, lat);
  }
  EXPECT_GT(worst, 8.0);
}
