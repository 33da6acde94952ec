// GNSS fusion on a synthetic drive with a known truth: a 2 km curved road at 20 m/s, the trajectory
// given in a map frame rotated and shifted from ENU and drifting (yaw-rate bias, scale error, as
// dead reckoning or odometry does), fixes at 10 Hz with 1 m white noise through a lever arm. The oracle
// is the truth itself: ATE, the bridged outage's steps, the rejected multipath jump, T_enu_map.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>

#include "roadslam/gnss_fusion/gnss_fusion.h"
#include "roadslam/gnss_fusion/gnss_fusion_online.h"

using namespace roadslam::gnss_fusion;

namespace {
struct Drive {
  std::vector<double> t;
  PoseVector truth;  ///< T_enu_node
  PoseVector odom;   ///< T_map_node, drifting
  Eigen::Isometry3d T_enu_map = Eigen::Isometry3d::Identity();
};

Drive makeDrive(double duration_s, double dt = 0.1, double scale = 1.002, double bias_deg_s = 0.01) {
  Drive d;
  const double v = 20.0;
  double x = 0, y = 0, yaw = 0.3, ox = 0, oy = 0, oyaw = 0;
  for (double t = 0; t <= duration_s + 1e-9; t += dt) {
    const double yaw_rate = 0.04 * std::sin(2 * M_PI * t / 40.0);  // gentle S-bends
    d.t.push_back(t);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, 0.5 * std::sin(t / 20.0));
    d.truth.push_back(T);
    Eigen::Isometry3d O = Eigen::Isometry3d::Identity();
    O.linear() = Eigen::AngleAxisd(oyaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    O.translation() = Eigen::Vector3d(ox, oy, 0);
    d.odom.push_back(O);
    x += v * dt * std::cos(yaw);
    y += v * dt * std::sin(yaw);
    yaw += yaw_rate * dt;
    // odometry: a scale error and a yaw-rate bias (0.2 % and 0.01 deg/s by default: a 2 km drift of
    // 4 m along and 20 m across), in a map frame = the first pose
    ox += scale * v * dt * std::cos(oyaw);
    oy += scale * v * dt * std::sin(oyaw);
    oyaw += (yaw_rate + bias_deg_s * M_PI / 180) * dt;
  }
  d.T_enu_map = d.truth[0] * d.odom[0].inverse();
  return d;
}

std::vector<GnssFactor> makeFixes(const Drive& d, const Eigen::Vector3d& lever, double sigma, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, sigma);
  std::vector<GnssFactor> f;
  for (size_t i = 0; i < d.t.size(); ++i) {
    GnssFactor g;
    g.t_s = d.t[i];
    g.p_enu = d.truth[i] * lever + Eigen::Vector3d(n(rng), n(rng), 1.5 * n(rng));
    g.cov = Eigen::Vector3d(sigma * sigma, sigma * sigma, 2.25 * sigma * sigma).asDiagonal();
    f.push_back(g);
  }
  return f;
}

/// rms position error [m]; \p horizontal: east and north only.
double ate(const PoseVector& est, const PoseVector& truth, bool horizontal = false) {
  double s = 0;
  for (size_t i = 0; i < est.size(); ++i) {
    const Eigen::Vector3d e = est[i].translation() - truth[i].translation();
    s += horizontal ? e.head<2>().squaredNorm() : e.squaredNorm();
  }
  return std::sqrt(s / static_cast<double>(est.size()));
}

GnssFusionParams params(const Eigen::Vector3d& lever, GnssOptimizer optimizer = GnssOptimizer::GaussNewton) {
  GnssFusionParams p;
  p.optimizer = optimizer;
  p.lever_x_m = lever.x();
  p.lever_y_m = lever.y();
  p.lever_z_m = lever.z();
  return p;
}

/// The online mode is causal: with every fix after t = 30 s moved 30 m east, the poses of the frames
/// up to 30 s (\p online, replayed with \p fixes) come out the same to 1e-12.
void expectCausal(const Drive& d, std::vector<GnssFactor> fixes, const GnssFusionParams& p,
                  const std::vector<std::optional<Eigen::Isometry3d>>& online) {
  for (auto& f : fixes) {
    if (f.t_s > 30) f.p_enu.x() += 30;
  }
  const auto online_late = replayOnline(d.t, d.odom, fixes, p);
  for (size_t i = 0; i < d.t.size() && d.t[i] <= 30; ++i) {
    ASSERT_EQ(online[i].has_value(), online_late[i].has_value()) << "frame " << i;
    if (online[i]) {
      EXPECT_TRUE(online[i]->isApprox(*online_late[i], 1e-12)) << "frame " << i;
    }
  }
}
}  // namespace

// The batch oracle tests run on each solver ([gnss_fusion] optimizer): the own IRLS Gauss-Newton and Ceres.
class GnssFusionSolver : public ::testing::TestWithParam<GnssOptimizer> {};
INSTANTIATE_TEST_SUITE_P(Optimizers, GnssFusionSolver, ::testing::Values(GnssOptimizer::GaussNewton, GnssOptimizer::Ceres),
                         [](const auto& info) { return info.param == GnssOptimizer::Ceres ? "ceres" : "gauss_newton"; });

TEST_P(GnssFusionSolver, BeatsBothInputsAndFindsTheMapFrame) {
  const Drive d = makeDrive(100);
  const Eigen::Vector3d lever(0.5, 0.2, 1.5);
  const auto fixes = makeFixes(d, lever, 1.0, 7);
  const GnssFusionResult r = fuseGnss(d.t, d.odom, fixes, params(lever, GetParam()));
  ASSERT_TRUE(r.ok) << r.status;
  const double fused = ate(r.T_enu_node, d.truth);
  // the inputs alone: the odometry placed by the true start, the fixes as positions (less the lever arm)
  PoseVector odo_enu, fix_only;
  for (size_t i = 0; i < d.t.size(); ++i) {
    odo_enu.push_back(d.T_enu_map * d.odom[i]);
    Eigen::Isometry3d F = d.truth[i];
    F.translation() = fixes[i].p_enu - d.truth[i].rotation() * lever;
    fix_only.push_back(F);
  }
  const double odo = ate(odo_enu, d.truth), gnss = ate(fix_only, d.truth);
  EXPECT_LT(ate(r.T_enu_node, d.truth, true), 0.30) << "odometry " << odo << " gnss " << gnss;
  EXPECT_LT(fused, 0.40);
  EXPECT_LT(fused, 0.5 * gnss);
  EXPECT_LT(fused, 0.1 * odo);
  EXPECT_EQ(r.rejected, 0u);
  EXPECT_EQ(r.used, fixes.size());
  // T_enu_map of a drifting trajectory is its best fit, close to the start's in heading
  EXPECT_LT(Eigen::AngleAxisd(r.T_enu_map.rotation().transpose() * d.T_enu_map.rotation()).angle(), 0.02);
}

TEST_P(GnssFusionSolver, MapToEnuOfAnUndriftedTrajectory) {
  const Drive d = makeDrive(60, 0.1, 1.0, 0.0);
  const Eigen::Vector3d lever(0.5, 0.2, 1.5);
  const GnssFusionResult r = fuseGnss(d.t, d.odom, makeFixes(d, lever, 1.0, 5), params(lever, GetParam()));
  ASSERT_TRUE(r.ok) << r.status;
  // the truth's z wobbles by 0.5 m where the odometry is flat: compare horizontally and in heading
  EXPECT_LT((r.T_enu_map.translation() - d.T_enu_map.translation()).head<2>().norm(), 0.15);
  EXPECT_LT(Eigen::AngleAxisd(r.T_enu_map.rotation().transpose() * d.T_enu_map.rotation()).angle(), 0.002);
}

TEST_P(GnssFusionSolver, OutageBridgedAndMultipathRejected) {
  const Drive d = makeDrive(120);
  const Eigen::Vector3d lever(0.5, 0.0, 1.5);
  auto all = makeFixes(d, lever, 1.0, 11);
  std::vector<GnssFactor> fixes;
  size_t jumps = 0;
  for (auto f : all) {
    if (f.t_s >= 40 && f.t_s < 70) continue;  // 30 s outage
    if (f.t_s >= 90 && f.t_s < 93) {         // 3 s of a 50 m multipath jump, the receiver unaware
      f.p_enu.x() += 50;
      ++jumps;
    }
    fixes.push_back(f);
  }
  const GnssFusionResult r = fuseGnss(d.t, d.odom, fixes, params(lever, GetParam()));
  ASSERT_TRUE(r.ok) << r.status;
  EXPECT_EQ(r.rejected, jumps);
  for (size_t k = 0; k < fixes.size(); ++k) {
    const bool jump = fixes[k].t_s >= 90 && fixes[k].t_s < 93;
    EXPECT_EQ(r.fix_use[k], jump ? FixUse::Rejected : FixUse::Used) << "t " << fixes[k].t_s;
  }
  // no jump on reacquisition: each step's error against the true step stays small
  double worst_step = 0, worst_err = 0;
  for (size_t i = 1; i < d.t.size(); ++i) {
    const Eigen::Vector3d de = (r.T_enu_node[i].translation() - r.T_enu_node[i - 1].translation()) -
                               (d.truth[i].translation() - d.truth[i - 1].translation());
    worst_step = std::max(worst_step, de.norm());
    worst_err = std::max(worst_err, (r.T_enu_node[i].translation() - d.truth[i].translation()).norm());
  }
  EXPECT_LT(worst_step, 0.2);
  EXPECT_LT(ate(r.T_enu_node, d.truth, true), 0.4);
  EXPECT_LT(worst_err, 2.0);  // in the middle of the 30 s (600 m) outage
}

TEST(GnssFusion, TooFewFixesOrNoMotionIsAStatus) {
  const Drive d = makeDrive(10);
  std::vector<GnssFactor> two(makeFixes(d, Eigen::Vector3d::Zero(), 1.0, 3));
  two.resize(2);
  const auto r = fuseGnss(d.t, d.odom, two, GnssFusionParams{});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.status.find("fewer than 3"), std::string::npos);
  EXPECT_EQ(r.T_enu_node.size(), d.t.size());
  // standing still: the heading cannot be observed
  PoseVector still(d.t.size(), Eigen::Isometry3d::Identity());
  const auto s = fuseGnss(d.t, still, makeFixes(makeDrive(0.0, 0.1), Eigen::Vector3d::Zero(), 0.1, 3), GnssFusionParams{});
  EXPECT_FALSE(s.ok);
}

// The online mode: causal (a frame's pose does not change when later fixes do) and, on the drifting
// drive (60 s, a 20 s window to keep the test short), closer to the truth than the fixes alone and
// the odometry alone.
TEST(GnssFusionOnline, CausalAndBetterThanEitherInput) {
  const Drive d = makeDrive(60);
  const Eigen::Vector3d lever(0.5, 0.2, 1.5);
  const auto fixes = makeFixes(d, lever, 1.0, 7);
  GnssFusionParams p = params(lever);
  p.online_window_s = 20;
  GnssOnlineStats st;
  const auto online = replayOnline(d.t, d.odom, fixes, p, &st);
  expectCausal(d, fixes, p, online);
  PoseVector est, truth, odo_enu, fix_only;
  for (size_t i = 0; i < d.t.size(); ++i) {
    if (!online[i]) continue;
    est.push_back(*online[i]);
    truth.push_back(d.truth[i]);
    odo_enu.push_back(d.T_enu_map * d.odom[i]);
    Eigen::Isometry3d F = d.truth[i];
    F.translation() = fixes[i].p_enu - d.truth[i].rotation() * lever;
    fix_only.push_back(F);
  }
  ASSERT_GT(est.size(), d.t.size() * 9 / 10) << "anchored late";
  const double on = ate(est, truth, true), gnss = ate(fix_only, truth, true), odo = ate(odo_enu, truth, true);
  EXPECT_LT(on, 0.7 * gnss) << "online " << on << " gnss " << gnss << " odometry " << odo;
  EXPECT_LT(on, 0.3 * odo);
  std::cout << "online 2D ATE " << on << " m, fixes alone " << gnss << " m, odometry alone " << odo << " m\n";
  EXPECT_LE(st.failed, 2u);  // the first solves: fewer than 3 fixes, no motion yet
  EXPECT_GE(st.solves, 55u);
}

// The online yaw-rate bias state: on the drifting drive with the RAV4's order of gyro offset
// (0.4 deg/s, 8 deg over the 20 s window), the correction it carries converges to minus the drive's
// own bias (the oracle), the mode stays causal, and the error falls below the mode without the state.
TEST(GnssFusionOnline, YawRateBiasStateFindsTheDrivesBias) {
  const double bias_deg_s = 0.4;
  const Drive d = makeDrive(60, 0.1, 1.002, bias_deg_s);
  const Eigen::Vector3d lever(0.5, 0.2, 1.5);
  const auto fixes = makeFixes(d, lever, 1.0, 7);
  GnssFusionParams p = params(lever);
  p.online_window_s = 20;
  const auto plain = replayOnline(d.t, d.odom, fixes, p);
  p.online_yaw_rate_bias = true;
  GnssOnlineStats st;
  const auto online = replayOnline(d.t, d.odom, fixes, p, &st);
  expectCausal(d, fixes, p, online);
  PoseVector est, est_plain, truth;
  for (size_t i = 0; i < d.t.size(); ++i) {
    if (!online[i] || !plain[i] || d.t[i] < 20) continue;  // scored once a full window has passed
    est.push_back(*online[i]);
    est_plain.push_back(*plain[i]);
    truth.push_back(d.truth[i]);
  }
  EXPECT_NEAR(st.yaw_rate_correction_radps * 180 / M_PI, -bias_deg_s, 0.05);
  EXPECT_GT(st.bias_updates, 20u);
  const double on = ate(est, truth, true), on_plain = ate(est_plain, truth, true);
  EXPECT_LT(on, 0.8 * on_plain) << "with the bias state " << on << " m, without " << on_plain << " m";
  std::cout << "yaw-rate correction " << st.yaw_rate_correction_radps * 180 / M_PI << " deg/s; 2D ATE from t = 20 s "
            << on << " m with the state, " << on_plain << " m without\n";
}
