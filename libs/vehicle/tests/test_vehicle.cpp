// Unit tests: vehicle ini loading (every shipped ini), signal mapping with add/sign/negate, and the
// dead reckoning against closed-form motions.
#include <roadslam/common/config.h>
#include <roadslam/vehicle/dead_reckoning.h>
#include <roadslam/vehicle/vehicle_state.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>
#include <fstream>
#include <unistd.h>
#include <limits>
#include <filesystem>

using namespace roadslam::vehicle;
using roadslam::can::CanFrame;
namespace fs = std::filesystem;

namespace {
constexpr double kPi = 3.14159265358979323846;

const char* kDbc = R"(BO_ 100 WHEELS: 8 X
 SG_ FL : 0|16@1+ (0.01,0) [0|0] "km/h" X
 SG_ FR : 16|16@1+ (0.01,0) [0|0] "km/h" X
 SG_ RL : 32|16@1+ (0.01,0) [0|0] "km/h" X
 SG_ RR : 48|16@1+ (0.01,0) [0|0] "km/h" X
BO_ 101 YAW: 4 X
 SG_ RATE : 0|16@1+ (0.01,0) [0|0] "deg/s" X
 SG_ RATE_SIGN : 16|1@1+ (1,0) [0|0] "" X
 SG_ STEER : 24|8@1- (1,0) [0|0] "deg" X
 SG_ STEER_FINE : 17|4@1+ (0.1,0) [0|0] "deg" X
)";

VehicleParams testParams() {
  mrpt::config::CConfigFileMemory cfg;
  cfg.setContent(std::string(R"([vehicle]
name = test
dbc = x.dbc
wheelbase_m = 2.5
track_width_m = 1.5
steering_ratio = 10
wheel_fl = WHEELS.FL
wheel_fl_unit = kmh
wheel_fr = WHEELS.FR
wheel_fr_unit = kmh
wheel_rl = WHEELS.RL
wheel_rl_unit = kmh
wheel_rr = WHEELS.RR
wheel_rr_unit = kmh
yaw_rate = YAW.RATE
yaw_rate_unit = deg_s
yaw_rate_negate_if = YAW.RATE_SIGN
steering_angle = YAW.STEER
steering_angle_add = YAW.STEER_FINE
steering_angle_unit = deg
steering_angle_sign = -1
)"));
  VehicleParams p;
  p.loadFromConfigFile(cfg, "vehicle");
  return p;
}

CanFrame wheels(double t, double kmh) {
  CanFrame f;
  f.t_us = static_cast<std::int64_t>(std::llround(t * 1e6));
  f.id = 100;
  f.len = 8;
  const auto raw = static_cast<std::uint16_t>(std::lround(kmh * 100));
  for (int w = 0; w < 4; ++w) {
    f.data[2 * w] = raw & 0xFF;
    f.data[2 * w + 1] = raw >> 8;
  }
  return f;
}

CanFrame yaw(double t, double deg_s, int steer_deg = 0, int fine = 0) {
  CanFrame f;
  f.t_us = static_cast<std::int64_t>(std::llround(t * 1e6));
  f.id = 101;
  f.len = 4;
  const auto raw = static_cast<std::uint16_t>(std::lround(std::abs(deg_s) * 100));
  f.data[0] = raw & 0xFF;
  f.data[1] = raw >> 8;
  f.data[2] = static_cast<std::uint8_t>((deg_s < 0 ? 1 : 0) | (fine << 1));
  f.data[3] = static_cast<std::uint8_t>(static_cast<std::int8_t>(steer_deg));
  return f;
}
}  // namespace

TEST(VehicleParams, EveryShippedIniLoadsAndMapsExistingSignals) {
  const fs::path dir = fs::path(ROADSLAM_SOURCE_DIR) / "ini" / "vehicles";
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".ini") continue;
    SCOPED_TRACE(e.path().string());
    // data_root in each ini is relative to the ini: ../shared/data for the real cars' DBCs (beside
    // the checkout), the ini's own folder for the simulator's DBC, which the project wrote itself
    const VehicleParams p = loadVehicleIni(e.path().string());
    EXPECT_FALSE(p.name.empty());
    // a speed, and a way to turn or a position (tesla-model-s: speed and the car's own GNSS only)
    EXPECT_TRUE(p.at(Quantity::kWheelFL).present() || p.at(Quantity::kVehicleSpeed).present());
    EXPECT_TRUE(p.at(Quantity::kSteeringAngle).present() ||
                (p.at(Quantity::kLatitude).present() && p.at(Quantity::kLongitude).present()));
    ++n;
    if (!fs::exists(p.dbcPath())) {
      std::cout << "DBC " << p.dbcPath() << " absent: signal names not checked\n";
      continue;
    }
    const VehicleDecoder dec(p);  // throws when a mapped signal is not in the DBC
    mrpt::config::CConfigFileMemory out;
    p.saveToConfigFile(out, "vehicle");
    VehicleParams again;
    again.loadFromConfigFile(out, "vehicle");
    EXPECT_EQ(again.at(Quantity::kWheelRR).signal, p.at(Quantity::kWheelRR).signal);
    EXPECT_EQ(again.dbcPath(), p.dbcPath());
  }
  EXPECT_EQ(n, 7U);  // toyota-rav4-2017, honda-civic-2019, bmw-e9x, vw-mqb, hyundai-kia, tesla-model-s, roadslam-sim
}

TEST(VehicleParams, BadValuesNameTheKey) {
  mrpt::config::CConfigFileMemory cfg;
  cfg.setContent(std::string("[vehicle]\nwheel_fl = A.B\nwheel_fl_unit = furlong\n"));
  VehicleParams p;
  try {
    p.loadFromConfigFile(cfg, "vehicle");
    FAIL() << "no error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("wheel_fl_unit"), std::string::npos) << e.what();
  }
  cfg.setContent(std::string("[vehicle]\nwheel_fl_typo = A.B\n"));
  EXPECT_THROW(p.loadFromConfigFile(cfg, "vehicle"), std::runtime_error);
}

TEST(VehicleDecoder, AppliesUnitsAddAndSignFlags) {
  const VehicleParams p = testParams();
  VehicleDecoder dec(p, roadslam::can::parseDbc(kDbc));
  VehicleState s;
  EXPECT_EQ(dec.process(wheels(1.0, 36.0), s), kWheelMask);
  EXPECT_NEAR(s.speed(), 10.0, 1e-12);
  const UpdateMask m = dec.process(yaw(1.01, -5.0, -3, 5), s);
  EXPECT_EQ(m, bit(Quantity::kYawRate) | bit(Quantity::kSteeringAngle));
  EXPECT_NEAR(s.value(Quantity::kYawRate), -5.0 * kPi / 180, 1e-12);
  EXPECT_NEAR(s.value(Quantity::kSteeringAngle), -(-3 + 0.5) * kPi / 180, 1e-12);
  CanFrame short_frame = yaw(1.02, 1.0);
  short_frame.len = 1;
  EXPECT_EQ(dec.process(short_frame, s), 0U);
  EXPECT_EQ(dec.stats().short_frames, 1U);
}

// A candump log streamed up to given times: each frame once, in order, none past the time (the
// first one past it waits for the next call), its state as the decoder gives it; the log's bad line
// is counted, not fatal.
TEST(VehicleLogReader, ReadsEachFrameOnceUpToTheTimeGiven) {
  const fs::path dir = fs::temp_directory_path() / ("roadslam-vehicle-log-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "x.dbc") << kDbc;
  VehicleParams p = testParams();
  p.dbc = (dir / "x.dbc").string();
  std::vector<CanFrame> frames = {wheels(1.0, 36.0), yaw(1.05, -5.0), wheels(1.1, 72.0), yaw(1.15, 2.0), wheels(1.2, 18.0)};
  for (auto& f : frames) f.setInterface("can0");
  roadslam::can::writeCandumpFile((dir / "drive.log").string(), frames);
  std::ofstream(dir / "drive.log", std::ios::app) << "not a frame\n";
  VehicleLogReader log((dir / "drive.log").string(), p);
  std::vector<double> t, speed;
  auto keep = [&](const VehicleState& s, UpdateMask m) {
    t.push_back(s.t_s);
    speed.push_back(m & kWheelMask ? s.speed() : -1.0);
  };
  EXPECT_EQ(log.readUntil(0.5, keep), 0u);
  EXPECT_EQ(log.readUntil(1.1, keep), 3u);  // 1.0, 1.05 and 1.1 (at the time given)
  EXPECT_EQ(log.readUntil(1.1, keep), 0u);
  EXPECT_FALSE(log.ended());
  EXPECT_EQ(log.readUntil(std::numeric_limits<double>::infinity(), keep), 2u);
  EXPECT_TRUE(log.ended());
  const std::vector<double> t_log = {1.0, 1.05, 1.1, 1.15, 1.2};
  ASSERT_EQ(t.size(), t_log.size());
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(t[i], t_log[i], 1e-9);
  ASSERT_EQ(speed.size(), 5u);
  EXPECT_NEAR(speed[0], 10.0, 1e-9);
  EXPECT_EQ(speed[1], -1.0);
  EXPECT_NEAR(speed[2], 20.0, 1e-9);
  EXPECT_NEAR(speed[4], 5.0, 1e-9);
  EXPECT_EQ(log.logStats().bad, 1u);
  EXPECT_EQ(log.decoder().stats().used, 5u);
  fs::remove_all(dir);
}

TEST(DeadReckoning, CircleMatchesClosedForm) {
  // 10 m/s with 10 deg/s for 36 s: a full circle of radius v/w, back at the start.
  const VehicleParams p = testParams();
  VehicleDecoder dec(p, roadslam::can::parseDbc(kDbc));
  DeadReckoning dr(DeadReckoningParams{}, p);
  VehicleState s;
  Pose2D quarter;
  for (int i = 0; i <= 3600; ++i) {
    const double t = 100 + i * 0.01;
    dr.update(s, dec.process(yaw(t, 10.0), s));
    dr.update(s, dec.process(wheels(t + 0.001, 36.0), s));
    if (i == 900) quarter = dr.pose();
  }
  const double r = 10.0 / (10.0 * kPi / 180);
  EXPECT_NEAR(quarter.x_m, r, 0.05);
  EXPECT_NEAR(quarter.y_m, r, 0.05);
  EXPECT_NEAR(dr.pose().x_m, 0.0, 0.05);
  EXPECT_NEAR(dr.pose().y_m, 0.0, 0.05);
  EXPECT_NEAR(dr.stats().distance_m, 360.0, 0.1);
}

TEST(DeadReckoning, StandstillBiasIsRemoved) {
  const VehicleParams p = testParams();
  VehicleDecoder dec(p, roadslam::can::parseDbc(kDbc));
  DeadReckoning dr(DeadReckoningParams{}, p);
  VehicleState s;
  double t = 0;
  for (int i = 0; i < 300; ++i, t += 0.01) {  // 3 s standing with a 0.5 deg/s offset
    dr.update(s, dec.process(wheels(t, 0.0), s));
    dr.update(s, dec.process(yaw(t + 0.001, 0.5), s));
  }
  EXPECT_NEAR(dr.yawRateBias(), 0.5 * kPi / 180, 1e-9);
  for (int i = 0; i < 1000; ++i, t += 0.01) {  // then straight at 20 m/s: heading must stay 0
    dr.update(s, dec.process(yaw(t, 0.5), s));
    dr.update(s, dec.process(wheels(t + 0.001, 72.0), s));
  }
  EXPECT_NEAR(dr.pose().yaw_rad, 0.0, 1e-9);
  EXPECT_NEAR(dr.pose().x_m, 200.0, 0.3);
  EXPECT_GT(dr.stats().standstill_s, 2.5);
}

TEST(DeadReckoning, BicycleModelWithoutYawRateAndGapsReported) {
  VehicleParams p = testParams();
  p.map[static_cast<std::size_t>(Quantity::kYawRate)] = SignalMapping{};
  VehicleDecoder dec(p, roadslam::can::parseDbc(kDbc));
  DeadReckoning dr(DeadReckoningParams{}, p);
  VehicleState s;
  // Steering wheel -20 deg (sign -1 in the ini: left positive +20 deg), ratio 10: road wheel 2 deg.
  for (int i = 0; i <= 100; ++i) {
    const double t = i * 0.01 + (i > 50 ? 2.0 : 0.0);  // a 2 s gap in the middle
    dr.update(s, dec.process(yaw(t, 0.0, -20), s));
    dr.update(s, dec.process(wheels(t + 0.001, 36.0), s));
  }
  const double w = 10.0 * std::tan(2.0 * kPi / 180) / 2.5;
  EXPECT_NEAR(dr.pose().w_radps, w, 1e-9);
  EXPECT_EQ(dr.stats().gaps, 1U);
  EXPECT_NEAR(dr.pose().yaw_rad, w * 0.99, 1e-3);  // the gap is not integrated
}

TEST(DeadReckoning, RawIntegralsAndOnlineCalibrationSetters) {
  // Moving from the start (no standstill): the 0.5 deg/s offset turns the heading until a bias is set.
  const VehicleParams p = testParams();
  VehicleDecoder dec(p, roadslam::can::parseDbc(kDbc));
  DeadReckoning dr(DeadReckoningParams{}, p);
  VehicleState s;
  double t = 0;
  auto drive = [&](int steps) {
    for (int i = 0; i < steps; ++i, t += 0.01) {
      dr.update(s, dec.process(yaw(t, 0.5), s));
      dr.update(s, dec.process(wheels(t + 0.001, 72.0), s));
    }
  };
  drive(501);  // 5 s at 20 m/s after the first speed update
  const Pose2D a = dr.pose();
  EXPECT_NEAR(a.raw_yaw_rad, 0.5 * kPi / 180 * 5, 1e-7);
  EXPECT_NEAR(a.yaw_rad, a.raw_yaw_rad, 1e-12);
  EXPECT_NEAR(a.raw_distance_m, 100.0, 1e-3);
  dr.setYawRateBias(0.5 * kPi / 180);
  dr.setSpeedScale(1.01);
  EXPECT_EQ(dr.speedScale(), 1.01);
  drive(500);
  const Pose2D b = dr.pose();
  EXPECT_NEAR(b.yaw_rad, a.yaw_rad, 1e-12);                 // the bias now cancels the offset
  EXPECT_NEAR(b.raw_yaw_rad, 0.5 * kPi / 180 * 10, 1e-7);  // raw integrals ignore the calibration
  EXPECT_NEAR(b.raw_distance_m, 200.0, 1e-3);
  EXPECT_NEAR(std::hypot(b.x_m - a.x_m, b.y_m - a.y_m), 101.0, 1e-3);  // scaled speed
  EXPECT_NEAR(dr.stats().distance_m, 201.0, 1e-3);
}
