// The harder sensor and world models against analytic oracles: per-laser calibration offsets,
// 64-beam rings on a flat ground and sweep timing, the crowned road in the rays and in the ground
// truth, suspension pitch and roll, roughness, mixed pixels at a depth edge.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <cmath>

#include "roadslam/sim/simulator.h"
#include "sim_test_util.h"

using namespace roadslam;
using namespace roadslam::sim;
using sim::test::iniPath;

namespace {
constexpr double kDeg = M_PI / 180.0;

/// A straight 1 km road on flat ground with nothing on it: ground and (optionally) curbs only.
ScenarioParams emptyStraight() {
  ScenarioParams p;
  p.world.layout = "straight";
  p.world.length_m = 1000;
  p.world.curviness_m = 0;
  p.world.building_density = 0;
  p.world.pole_spacing_m = 0;
  p.world.tree_spacing_m = 0;
  p.world.parking_width_m = 0;
  p.world.sidewalk_width_m = 0;
  p.world.moving_cars = 0;
  p.lidar.range_noise_m = 0;
  p.lidar.dropout_prob = 0;
  p.lidar.jitter_deg = 0;
  p.trajectory.start_standing_s = 5;
  return p;
}

/// \p p_world in the frame of \p T (T_world_lidar).
Vec3 toLidar(const Pose3& T, const Vec3& p) {
  const double dx = p.x - T.t.x, dy = p.y - T.t.y, dz = p.z - T.t.z;
  const auto& R = T.R;
  return {R[0] * dx + R[3] * dy + R[6] * dz, R[1] * dx + R[4] * dy + R[7] * dz, R[2] * dx + R[5] * dy + R[8] * dz};
}
}  // namespace

// The ray goes along nominal + drawn offset; the output reports the nominal angles and the true
// range + the drawn range offset.
TEST(SimHard, CalibrationOffsetsAreExactlyTheDrawnOnes) {
  ScenarioParams p = ScenarioParams::fromFile(iniPath("urban-loop.ini"));
  p.duration_s = 0.05;
  p.lidar.range_noise_m = 0;
  p.lidar.jitter_deg = 0;
  p.lidar.calib_elevation_std_deg = 0.3;
  p.lidar.calib_azimuth_std_deg = 0.3;
  p.lidar.calib_range_std_m = 0.05;
  Simulator sim(p);
  test::VectorSink sink;
  std::vector<TrueReturn> truth;
  sim.run(sink, &truth);
  ASSERT_GT(truth.size(), 5000u);
  const auto& cal = sim.lidar().calibration();
  int nonzero = 0;
  for (const auto& c : cal) nonzero += c.elevation_rad != 0 && c.azimuth_rad != 0 && c.range_m != 0;
  EXPECT_EQ(nonzero, 16);
  const Pose3 T = sim.lidar().lidarPose(0);  // standing still for 2 s
  double max_de = 0, max_da = 0, max_dr = 0;
  for (const TrueReturn& r : truth) {
    const Vec3 q = toLidar(T, r.p_world);
    const double range = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
    const double el = std::atan2(q.z, std::hypot(q.x, q.y)), az = std::atan2(-q.y, q.x);
    const LaserCalibration& c = cal[r.laser];
    max_de = std::max(max_de, std::abs(el - LidarSimulator::elevationDeg(r.laser) * kDeg - c.elevation_rad));
    max_da = std::max(max_da, std::abs(std::remainder(az - r.azimuth_deg * kDeg - c.azimuth_rad, 2 * M_PI)));
    max_dr = std::max(max_dr, std::abs(r.range_m - range - c.range_m));
  }
  EXPECT_LT(max_de, 1e-9);
  EXPECT_LT(max_da, 1e-9);
  EXPECT_LT(max_dr, 2e-5) << "float range";
}

// HDL-64E standing on a flat ground 1.73 m below: every return of laser e lies at 1.73 / sin(-e),
// the rings of the lower block are complete (one point per column), and nothing above -0.83 deg
// (120 m) returns.
TEST(SimHard, Hdl64RingsOnAFlatGround) {
  ScenarioParams p = emptyStraight();
  p.lidar.model = "hdl64";
  p.lidar.max_range_m = 120;
  p.lidar.mount_height_m = 1.73;
  p.duration_s = 0.1;
  Simulator sim(p);
  std::vector<Scan> sweeps;
  const SimStats st = sim.runSweeps([&](uint64_t, Scan&& s) { sweeps.push_back(std::move(s)); });
  ASSERT_EQ(st.sweeps, 1u);
  ASSERT_EQ(sweeps.size(), 1u);
  const int N = sim.lidar().columnsPerSweep();
  EXPECT_EQ(N, 2084);
  std::vector<int> per_ring(64, 0);
  double max_err = 0;
  for (const ScanPoint& q : sweeps[0].points) {
    const int laser = 63 - q.ring;
    const double e = LidarSimulator::elevationDegHdl64(laser) * kDeg;
    ASSERT_LT(e, -0.8 * kDeg) << "laser " << laser;
    const double r = std::sqrt(double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
    max_err = std::max(max_err, std::abs(r - 1.73 / std::sin(-e)));
    ++per_ring[static_cast<std::size_t>(q.ring)];
  }
  EXPECT_LT(max_err, 1e-4);
  for (int laser = 32; laser < 64; ++laser) EXPECT_EQ(per_ring[static_cast<std::size_t>(63 - laser)], N) << laser;
  EXPECT_NEAR(LidarSimulator::elevationDegHdl64(0), 2.0, 1e-12);
  EXPECT_NEAR(LidarSimulator::elevationDegHdl64(63), -24.8, 1e-12);
}

// KITTI raw timing: a sweep starts behind the car (azimuth 180), turns clockwise, and its stamp is
// the moment it fires forward (azimuth 0), the middle of the sweep.
TEST(SimHard, Hdl64StampIsTheForwardFiring) {
  ScenarioParams p = emptyStraight();
  p.lidar.model = "hdl64";
  p.duration_s = 0.3;
  Simulator sim(p);
  std::vector<TrueReturn> truth;
  std::vector<double> stamps;
  sim.runSweeps([&](uint64_t, Scan&& s) { stamps.push_back(s.stamp_s); }, &truth);
  ASSERT_EQ(stamps.size(), 3u);
  for (uint64_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(stamps[k] - static_cast<double>(p.start_epoch_s), (k + 0.5) / p.lidar.rotation_hz, 1e-6);
    double first_az = -1, prev = -1, unwrapped = 0, t_forward = -1;
    int forward = 0;
    for (const TrueReturn& r : truth) {
      if (r.packet != k) continue;
      if (first_az < 0) first_az = prev = r.azimuth_deg;
      unwrapped += std::remainder(r.azimuth_deg - prev, 360.0);
      ASSERT_GE(std::remainder(r.azimuth_deg - prev, 360.0), 0.0) << "clockwise: azimuth never decreases";
      prev = r.azimuth_deg;
      if (r.azimuth_deg == 0) {
        t_forward = r.t_s;
        ++forward;
      }
    }
    EXPECT_EQ(first_az, 180.0);
    EXPECT_NEAR(unwrapped, 360.0 - 360.0 / sim.lidar().columnsPerSweep(), 1e-6);
    EXPECT_GT(forward, 0);
    EXPECT_NEAR(t_forward, sim.lidar().sweepStamp_s(k), 1e-12);
  }
}

// A crowned road (cross slope s, half width hw): the car in the right lane stands on the slope, so
// the ground truth rolls by atan(s) and rises by s (hw - lane/2); the ray caster's road points lie
// on z = s (hw - |y|).
TEST(SimHard, CrownedRoadInTheRaysAndInTheGroundTruth) {
  ScenarioParams p = emptyStraight();
  p.world.road_cross_slope = 0.03;
  p.world.sidewalk_width_m = 3;
  p.duration_s = 0.1;
  Simulator sim(p);
  const double hw = sim.world().roads[0].half_width_m, lane = p.world.lane_width_m;
  for (const VehicleState& s : sim.trajectory().states()) {
    if (s.s_m < 20 || s.s_m > 900) continue;
    ASSERT_NEAR(s.roll, std::atan(0.03), 1e-12) << s.t_s;
    ASSERT_NEAR(s.z, 0.03 * (hw - 0.5 * lane), 1e-9) << s.t_s;
  }
  test::VectorSink sink;
  std::vector<TrueReturn> truth;
  sim.run(sink, &truth);
  int on_road = 0;
  double max_err = 0;
  for (const TrueReturn& r : truth) {  // ahead: behind the road's start the crown goes on
    if (std::abs(r.p_world.y) > hw - 0.05 || r.p_world.z > 0.3 || r.p_world.x < 0) continue;
    ++on_road;
    max_err = std::max(max_err, std::abs(r.p_world.z - 0.03 * (hw - std::abs(r.p_world.y))));
  }
  EXPECT_GT(on_road, 1000);
  EXPECT_LT(max_err, 1e-6);
}

// Suspension: pitch = -k_pitch a (nose down when braking), roll = k_roll v yaw_rate, with a and the
// yaw rate taken from the ground-truth table by differences (not the table's own accel column),
// read back from the ground-truth lidar pose.
TEST(SimHard, SuspensionPitchAndRollFollowTheAccelerations) {
  ScenarioParams p = ScenarioParams::fromFile(iniPath("urban-loop.ini"));
  p.trajectory.k_pitch_deg_per_mps2 = 0.2;
  p.trajectory.k_roll_deg_per_mps2 = 0.5;
  const Simulator sim(p);
  const auto& st = sim.trajectory().states();
  int braking = 0, turning = 0;
  for (std::size_t i = 1; i + 1 < st.size(); ++i) {
    const double a = (st[i + 1].speed_mps - st[i - 1].speed_mps) / 0.02;
    const double a_prev = (st[i].speed_mps - st[i - 1].speed_mps) / 0.01, a_next = (st[i + 1].speed_mps - st[i].speed_mps) / 0.01;
    const double yaw_rate = std::remainder(st[i + 1].yaw - st[i - 1].yaw, 2 * M_PI) / 0.02;
    const Pose3 T = sim.lidar().lidarPose(st[i].t_s);  // T_world_lidar, mount not tilted
    const double pitch = std::asin(-T.R[6]), roll = std::atan2(T.R[7], T.R[8]);
    if (std::abs(a_prev - a_next) < 1e-3) {  // inside a constant-acceleration stretch
      ASSERT_NEAR(pitch, -0.2 * kDeg * a, 2e-5) << st[i].t_s;
      braking += a < -0.5;
    }
    if (std::abs(yaw_rate) > 0.05 && std::abs(a) < 1e-3) {
      ASSERT_NEAR(roll, 0.5 * kDeg * st[i].speed_mps * yaw_rate, 2e-4) << st[i].t_s;
      ++turning;
    }
  }
  EXPECT_GT(braking, 100);
  EXPECT_GT(turning, 100);
}

// Roughness: the height field has the configured standard deviation and mean ~0, and the ray
// caster's ground points lie on it.
TEST(SimHard, RoughGroundHasItsStdDevAndTheRaysLandOnIt) {
  ScenarioParams p = emptyStraight();
  p.world.road_roughness_m = 0.02;
  p.duration_s = 0.1;
  Simulator sim(p);
  const World& w = sim.world();
  double sum = 0, sum2 = 0;
  int n = 0;
  for (double x = 0; x < 200; x += 0.37)
    for (double y = -50; y < 50; y += 0.41, ++n) {
      const double h = w.surface.roughness(x, y);
      sum += h;
      sum2 += h * h;
    }
  EXPECT_NEAR(sum / n, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.02, 0.003);
  test::VectorSink sink;
  std::vector<TrueReturn> truth;
  sim.run(sink, &truth);
  std::vector<double> err;
  for (const TrueReturn& r : truth) err.push_back(std::abs(r.p_world.z - w.surfaceHeight(r.p_world.x, r.p_world.y)));
  ASSERT_GT(err.size(), 10000u);
  std::sort(err.begin(), err.end());
  EXPECT_LT(err.back(), 1e-5);
}

// A depth edge: a box 10 m ahead in front of a wall 20 m ahead. Without divergence every range is
// 10 m or 20 m; with divergence and mixed_pixel_prob = 1 the footprints on the box's edge return
// ranges in between; with mixed_pixel_prob = 0 they never do.
TEST(SimHard, MixedPixelsOnlyAtDepthEdgesWithAFootprint) {
  auto inBetween = [](double div_mrad, double prob) {
    ScenarioParams p = emptyStraight();
    p.duration_s = 0.5;
    p.lidar.beam_divergence_mrad = div_mrad;
    p.lidar.mixed_pixel_prob = prob;
    p.lidar.min_signal = 0;
    Simulator sim(p);
    World& w = const_cast<World&>(sim.world());
    const Pose3 T = sim.lidar().lidarPose(0);
    Prism box;  // front face at x = 10 m ahead of the lidar, left edge at y = 0
    box.cx = T.t.x + 10.5;
    box.cy = T.t.y - 1.0;
    box.hu = 0.5;
    box.hv = 1.0;
    box.zb = -1;
    box.zt = 5;
    Prism wall = box;
    wall.cx = T.t.x + 20.5;
    wall.cy = T.t.y;
    wall.hv = 20;
    w.prisms = {box, wall};
    w.buildGrid(w.xmin(), w.ymin(), w.xmax(), w.ymax(), 5);
    test::VectorSink sink;
    std::vector<TrueReturn> truth;
    sim.run(sink, &truth);
    int between = 0, edge = 0;
    for (const TrueReturn& r : truth) {
      const double az = std::remainder(r.azimuth_deg, 360.0);
      if (std::abs(az) > 5 || std::abs(LidarSimulator::elevationDeg(r.laser)) > 5) continue;
      const double x = r.range_m * std::cos(az * kDeg);
      between += x > 10.05 && x < 19.95;
      edge += std::abs(az) < 0.5;
    }
    EXPECT_GT(edge, 0);
    return between;
  };
  EXPECT_EQ(inBetween(0, 0), 0);
  EXPECT_EQ(inBetween(3, 0), 0);
  EXPECT_GT(inBetween(3, 1), 10);
}

// The hard scenarios turn every new key on; they save and reload to the same ini.
TEST(SimHard, HardScenariosSaveAndReloadIdentically) {
  for (const char* name : {"urban-loop-hard.ini", "highway-hard.ini", "city-hdl64.ini"}) {
    SCOPED_TRACE(name);
    const ScenarioParams a = ScenarioParams::fromFile(iniPath(name));
    EXPECT_GT(a.lidar.beam_divergence_mrad, 0);
    EXPECT_GT(a.lidar.mixed_pixel_prob, 0);
    EXPECT_GT(a.lidar.calib_elevation_std_deg, 0);
    EXPECT_GT(a.world.road_cross_slope, 0);
    EXPECT_GT(a.world.road_roughness_m, 0);
    EXPECT_GT(a.world.hedge_prob, 0);
    EXPECT_GT(a.trajectory.k_pitch_deg_per_mps2, 0);
    mrpt::config::CConfigFileMemory cfg, cfg2;
    a.saveToConfigFile(cfg);
    ScenarioParams b;
    b.loadFromConfigFile(cfg);
    b.saveToConfigFile(cfg2);
    EXPECT_EQ(cfg.getContent(), cfg2.getContent());
  }
  EXPECT_TRUE(ScenarioParams::fromFile(iniPath("city-hdl64.ini")).lidar.hdl64());
}

TEST(SimHard, BadNewValuesAreNamed) {
  auto message = [](const char* section, const char* key, const char* value) {
    mrpt::config::CConfigFileMemory cfg;
    cfg.write(section, key, value);
    ScenarioParams p;
    try {
      p.loadFromConfigFile(cfg);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("lidar", "model", "hdl32").find("hdl32"), std::string::npos);
  EXPECT_NE(message("lidar", "mixed_pixel_prob", "0.5").find("beam_divergence_mrad"), std::string::npos);
  EXPECT_NE(message("world", "road_cross_slope", "0.5").find("road_cross_slope"), std::string::npos);
  EXPECT_NE(message("trajectory", "k_pich_deg_per_mps2", "0.1").find("k_pich_deg_per_mps2"), std::string::npos);
}

// Hedges and canopy lobes are porous foliage spheres: turning them on adds many.
TEST(SimHard, VegetationAddsFoliageSpheres) {
  ScenarioParams p = ScenarioParams::fromFile(iniPath("urban-loop.ini"));
  const Simulator plain(p);
  p.world.hedge_prob = 1;
  p.world.canopy_lobes = 3;
  const Simulator green(p);
  EXPECT_GT(green.world().spheres.size(), 4 * plain.world().spheres.size());
  for (const Sphere& s : green.world().spheres) ASSERT_EQ(s.material, Material::Foliage);
  EXPECT_GT(materialProps(Material::Foliage).porosity, 0.0f);
}
