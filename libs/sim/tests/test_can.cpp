// The simulator's CAN traffic, decoded back with libs/vehicle and the shipped vehicle ini
// (ini/vehicles/roadslam-sim.ini): speeds and yaw rates match the trajectory within the configured
// errors, the standstill bias estimator recovers the yaw-rate bias, runs are deterministic, and
// runToDirectory writes can.log and names the DBC in summary.json.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "roadslam/can/candump.h"
#include "roadslam/sim/outputs.h"
#include "roadslam/vehicle/dead_reckoning.h"
#include "roadslam/vehicle/vehicle_state.h"
#include "sim_test_util.h"

using namespace roadslam;
using namespace roadslam::sim;
using vehicle::Quantity;

namespace {
constexpr double kDeg = M_PI / 180;
const std::string kVehicleIni = std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/roadslam-sim.ini";

struct Errors {
  double yaw_max = 0, yaw_mean = 0, rear_max = 0, speed_max = 0;  // |measured - expected| [rad/s], [m/s]
  std::size_t yaw_n = 0, wheel_n = 0;
  double bias_estimate = 0;  // DeadReckoning's standstill estimate [rad/s]
};

Errors decodeAgainstTruth(const Simulator& sim, const std::vector<can::CanFrame>& frames) {
  const CanParams& p = sim.params().can;
  vehicle::VehicleDecoder dec(vehicle::loadVehicleIni(kVehicleIni));
  vehicle::DeadReckoning dr(vehicle::DeadReckoningParams{}, dec.params());
  vehicle::VehicleState st;
  Errors e;
  const double scale = 1 + p.wheel_speed_scale_error, tw = sim.params().trajectory.track_width_m;
  for (const auto& f : frames) {
    const vehicle::UpdateMask m = dec.process(f, st);
    dr.update(st, m);
    // Every message is sent less than 10 ms after the 10 ms step whose state it carries.
    const int64_t step = (f.t_us - sim.params().start_epoch_s * 1000000) / 10000;
    const VehicleState s = sim.trajectory().at(static_cast<double>(step) * Trajectory::kStep_s);
    if (m & vehicle::bit(Quantity::kYawRate)) {
      const double err = st.value(Quantity::kYawRate) - s.yaw_rate_rps;
      e.yaw_max = std::max(e.yaw_max, std::abs(err - p.yaw_rate_bias_radps));
      e.yaw_mean += err;
      ++e.yaw_n;
    }
    if (m & vehicle::bit(Quantity::kWheelRL)) {
      e.rear_max = std::max(e.rear_max, std::abs(st.value(Quantity::kWheelRL) - scale * std::abs(s.speed_mps - s.yaw_rate_rps * tw / 2)));
      e.rear_max = std::max(e.rear_max, std::abs(st.value(Quantity::kWheelRR) - scale * std::abs(s.speed_mps + s.yaw_rate_rps * tw / 2)));
      ++e.wheel_n;
    }
    if (m & vehicle::bit(Quantity::kVehicleSpeed))
      e.speed_max = std::max(e.speed_max, std::abs(st.value(Quantity::kVehicleSpeed) - scale * s.speed_mps));
  }
  e.yaw_mean /= std::max<std::size_t>(1, e.yaw_n);
  e.bias_estimate = dr.yawRateBias();
  return e;
}
}  // namespace

TEST(SimCan, DecodedSpeedsAndYawRatesMatchTheDriveWithinTheConfiguredErrors) {
  auto sp = ScenarioParams::fromFile(test::iniPath("urban-loop.ini"));
  sp.duration_s = 60;
  const Simulator sim(sp);
  const auto frames = simulateCan(sim, sp.duration_s);
  // 100 Hz wheel speeds and yaw rate, 50 Hz speed and steering, 10 Hz gear
  EXPECT_EQ(frames.size(), 6001U * 2 + 3001U * 2 + 601U);
  const Errors e = decodeAgainstTruth(sim, frames);
  const CanParams& p = sp.can;
  std::cout << "yaw max err " << e.yaw_max / kDeg << " deg/s, mean " << e.yaw_mean / kDeg
            << " deg/s; rear wheels max err " << e.rear_max * 3.6 << " km/h; bias estimate "
            << e.bias_estimate / kDeg << " deg/s\n";
  EXPECT_EQ(e.yaw_n, 6001U);
  EXPECT_EQ(e.wheel_n, 6001U);
  // 5 sigma of the noise plus half an LSB of the DBC (0.01 deg/s, 0.01 km/h)
  EXPECT_LT(e.yaw_max, 5 * p.yaw_rate_noise_radps + 0.005 * kDeg);
  EXPECT_LT(e.rear_max, 5 * p.wheel_speed_noise_mps + 0.005 / 3.6);
  EXPECT_LT(e.speed_max, 5 * p.wheel_speed_noise_mps + 0.005 / 3.6);
  EXPECT_NEAR(e.yaw_mean, p.yaw_rate_bias_radps, 0.005 * kDeg);
  // 2 s standing at the start: the dead reckoning's standstill estimator finds the bias
  EXPECT_NEAR(e.bias_estimate, p.yaw_rate_bias_radps, 0.02 * kDeg);
}

TEST(SimCan, DeterministicForASeedAndConfigurable) {
  auto sp = ScenarioParams::fromFile(test::iniPath("tunnel.ini"));
  const Simulator sim(sp);
  const auto a = simulateCan(sim, 5.0), b = simulateCan(sim, 5.0);
  EXPECT_TRUE(a == b);
  EXPECT_FALSE(a == simulateCan(sim, sp.can, sp.seed + 1, 5.0));
  CanParams bad = sp.can;
  bad.dbc = "/nonexistent/x.dbc";
  try {
    simulateCan(sim, bad, 1, 1.0);
    FAIL() << "missing DBC accepted";
  } catch (const std::exception& ex) {
    EXPECT_NE(std::string(ex.what()).find("/nonexistent/x.dbc"), std::string::npos) << ex.what();
  }
}

TEST(SimCan, RunToDirectoryWritesCanLogAndNamesTheDbc) {
  auto sp = ScenarioParams::fromFile(test::iniPath("tunnel.ini"));
  sp.duration_s = 1.0;
  sp.can.yaw_rate_bias_radps = 0.5 * kDeg;
  Simulator sim(sp);
  test::TempDir dir("can");
  OutputOptions opt;
  opt.dir = dir.str();
  const RunReport rep = runToDirectory(sim, opt);
  can::CandumpStats cs;
  const auto frames = can::readCandumpFile(dir.str() + "/can.log", &cs);
  EXPECT_EQ(cs.bad, 0U);
  const auto want = simulateCan(sim, rep.stats.duration_s);
  ASSERT_EQ(frames.size(), want.size());
  for (std::size_t i = 0; i < frames.size(); ++i) ASSERT_TRUE(frames[i] == want[i]) << i << ": " << can::formatCandumpLine(frames[i]) << can::formatCandumpLine(want[i]);
  const auto j = nlohmann::json::parse(test::readAll(dir.str() + "/summary.json"));
  EXPECT_EQ(j.at("can_frames").get<std::size_t>(), frames.size());
  EXPECT_EQ(j.at("can_dbc").get<std::string>(), std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/roadslam-sim.dbc");
  // the used parameters are written and load back
  const auto used = ScenarioParams::fromFile(dir.str() + "/scenario_used.ini");
  EXPECT_NEAR(used.can.yaw_rate_bias_radps, 0.5 * kDeg, 1e-9);
}

// Independent oracle: python3-canmatrix decodes the simulated log with our DBC, and its yaw rates and
// rear-left wheel speeds match the drive (truth + bias, 1.005 x truth) within 5 sigma + half an LSB.
TEST(SimCan, CanmatrixDecodesTheSimulatedLogToTheDrive) {
  if (std::system("/usr/bin/python3 -c 'import canmatrix' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3-canmatrix not importable by /usr/bin/python3";
  auto sp = ScenarioParams::fromFile(test::iniPath("urban-loop.ini"));
  const Simulator sim(sp);
  const auto frames = simulateCan(sim, 20.0);
  test::TempDir dir("canmatrix");
  const std::string log = dir.str() + "/can.log", out = dir.str() + "/raw.txt";
  can::writeCandumpFile(log, frames);
  const std::string script = std::string(ROADSLAM_SOURCE_DIR) + "/libs/can/tests/canmatrix_decode.py";
  ASSERT_EQ(std::system(("/usr/bin/python3 " + script + " " + sp.can.dbcPath() + " " + log + " " +
                         std::to_string(frames.size()) + " > " + out + " 2>/dev/null").c_str()), 0);
  std::ifstream in(out);
  std::size_t i = 0, yaw_n = 0, wheel_n = 0;
  std::string name;
  long long raw = 0;
  const double tw = sp.trajectory.track_width_m;
  while (in >> i >> name >> raw) {
    ASSERT_LT(i, frames.size());
    const int64_t step = (frames[i].t_us - sp.start_epoch_s * 1000000) / 10000;
    const VehicleState s = sim.trajectory().at(static_cast<double>(step) * Trajectory::kStep_s);
    if (name == "YAW_RATE.YAW_RATE") {  // 16-bit signed, 0.01 deg/s
      const double v = static_cast<double>(raw >= 32768 ? raw - 65536 : raw) * 0.01 * kDeg;
      EXPECT_LT(std::abs(v - s.yaw_rate_rps - sp.can.yaw_rate_bias_radps), 5 * sp.can.yaw_rate_noise_radps + 0.005 * kDeg) << i;
      ++yaw_n;
    } else if (name == "WHEEL_SPEEDS.WHEEL_SPEED_RL") {  // 0.01 km/h
      const double v = static_cast<double>(raw) * 0.01 / 3.6;
      const double want = (1 + sp.can.wheel_speed_scale_error) * std::abs(s.speed_mps - s.yaw_rate_rps * tw / 2);
      EXPECT_LT(std::abs(v - want), 5 * sp.can.wheel_speed_noise_mps + 0.005 / 3.6) << i;
      ++wheel_n;
    }
  }
  EXPECT_EQ(yaw_n, 2001U);
  EXPECT_EQ(wheel_n, 2001U);
}
