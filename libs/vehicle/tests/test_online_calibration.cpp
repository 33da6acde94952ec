// OnlineCalibrator against a synthetic drive whose gyro bias and wheel-speed scale are known (the
// oracle), with reference (LiDAR-like) noise and injected outliers; DeadReckoning's raw integrals and
// calibration setters.
#include <roadslam/vehicle/dead_reckoning.h>
#include <roadslam/vehicle/online_calibration.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace roadslam::vehicle;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180;

struct Drive {
  double bias_radps = -0.4 * kDeg;    // RAV4-like gyro offset
  double wheel_error = -0.009;        // reported / true wheel speed - 1 (RAV4: 0.9 % short)
  double ref_yaw_sigma_rad = 1e-4;    // reference yaw error per interval
  double ref_dist_sigma_m = 0.01;     // reference translation error per interval
  int outlier_every = 0;              // every n-th interval the reference yaw is 0.05 rad off
};

/// 10 Hz intervals of a weaving drive (speed 9-15 m/s, yaw rate up to 5.7 deg/s).
CalibrationInterval interval(const Drive& d, int i, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  const double dt = 0.1, t = i * dt;
  const double v = 12 + 3 * std::sin(0.1 * t), w = 0.1 * std::sin(0.05 * t);
  CalibrationInterval c;
  c.dt_s = dt;
  c.raw_yaw_rad = (w + d.bias_radps) * dt + 0.05 * kDeg * std::sqrt(dt / 100) * n(rng);  // 100 Hz gyro noise
  c.raw_distance_m = v * dt * (1 + d.wheel_error);
  c.ref_yaw_rad = w * dt + d.ref_yaw_sigma_rad * n(rng);
  c.ref_distance_m = v * dt + d.ref_dist_sigma_m * n(rng);
  if (d.outlier_every > 0 && i % d.outlier_every == d.outlier_every / 2) c.ref_yaw_rad += 0.05;
  return c;
}
}  // namespace

TEST(OnlineCalibration, RecoversBiasAndScaleOfASyntheticDrive) {
  const Drive d;
  OnlineCalibrator cal;
  std::mt19937 rng(7);
  size_t bias_only = 0;
  for (int i = 0; i < 1200; ++i) {
    if (i == 30) {  // 3 s (~37 m) in: not enough time for the bias, not enough distance for the scale
      EXPECT_FALSE(cal.yawRateBias().has_value());
      EXPECT_FALSE(cal.speedScale().has_value());
    }
    bias_only += cal.add(interval(d, i, rng)) == CalibrationUse::BiasOnly;
  }
  ASSERT_TRUE(cal.yawRateBias().has_value());
  ASSERT_TRUE(cal.speedScale().has_value());
  std::printf("bias %.4f deg/s (true %.4f), scale %.5f (true %.5f), turning intervals %zu\n",
              *cal.yawRateBias() / kDeg, d.bias_radps / kDeg, *cal.speedScale(), 1 / (1 + d.wheel_error), bias_only);
  EXPECT_NEAR(*cal.yawRateBias(), d.bias_radps, 0.02 * kDeg);
  EXPECT_NEAR(*cal.speedScale(), 1 / (1 + d.wheel_error), 0.002 / (1 + d.wheel_error));
  EXPECT_GT(bias_only, 100u);  // the turns above 5 deg/s fed the bias only
  EXPECT_EQ(cal.stats().rejected, 0u);
  EXPECT_NEAR(cal.stats().bias_time_s, 60.0, 0.15);  // the window
}

TEST(OnlineCalibration, OutliersAreRejectedNotAveraged) {
  Drive d;
  d.outlier_every = 37;
  OnlineCalibrator cal;
  std::mt19937 rng(11);
  for (int i = 0; i < 60; ++i) cal.add(interval(Drive{}, i, rng));  // 6 s clean start
  for (int i = 60; i < 1200; ++i) cal.add(interval(d, i, rng));
  ASSERT_TRUE(cal.yawRateBias().has_value());
  EXPECT_NEAR(*cal.yawRateBias(), d.bias_radps, 0.02 * kDeg);
  EXPECT_GE(cal.stats().rejected, 1140u / 37);
  // the control: averaging the same outliers in would move the bias by ~0.05 rad / 3.7 s = 0.8 deg/s
  OnlineCalibrationParams open;
  open.gate_yaw_rate_radps = 100;
  OnlineCalibrator naive(open);
  std::mt19937 rng2(11);
  for (int i = 0; i < 1200; ++i) naive.add(interval(i < 60 ? Drive{} : d, i, rng2));
  EXPECT_GT(std::abs(*naive.yawRateBias() - d.bias_radps), 0.5 * kDeg);
}

TEST(OnlineCalibration, LongOrEmptyIntervalsAreRejected) {
  OnlineCalibrator cal;
  CalibrationInterval c;
  c.dt_s = 0.0;
  EXPECT_EQ(cal.add(c), CalibrationUse::Rejected);
  c.dt_s = 2.0;
  EXPECT_EQ(cal.add(c), CalibrationUse::Rejected);
  c.dt_s = 0.1;
  c.ref_yaw_rad = std::nan("");
  EXPECT_EQ(cal.add(c), CalibrationUse::Rejected);
  c.ref_yaw_rad = 0;
  EXPECT_EQ(cal.add(c), CalibrationUse::BiasOnly);  // standing: no distance for the scale
  EXPECT_EQ(cal.stats().rejected, 3u);
}

TEST(OnlineCalibration, ParamsRoundTripAndBadValuesNameTheKey) {
  OnlineCalibrationParams p;
  p.window_s = 42;
  p.max_yaw_rate_radps = 3 * kDeg;
  p.enabled = false;
  mrpt::config::CConfigFileMemory cfg;
  p.saveToConfigFile(cfg, "vehicle_prior");
  OnlineCalibrationParams q;
  q.loadFromConfigFile(cfg, "vehicle_prior");
  EXPECT_EQ(q.window_s, 42);
  EXPECT_NEAR(q.max_yaw_rate_radps, 3 * kDeg, 1e-12);
  EXPECT_FALSE(q.enabled);
  cfg.write("vehicle_prior", "calibration_window_s", std::string("-1"));
  try {
    q.loadFromConfigFile(cfg, "vehicle_prior");
    FAIL() << "negative window accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("calibration_window_s"), std::string::npos);
  }
}
