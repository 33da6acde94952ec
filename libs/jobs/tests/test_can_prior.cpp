// roadslam-map's wheel-odometry prior: the simulated tunnel (a corridor the scans cannot measure along
// its axis) with the simulator's own CAN log of the same drive, against the exact ground truth; the
// prior's online calibration against the LiDAR and the CAN constraints in the pose graph.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/eval/trajectory_metrics.h"
#include "roadslam/jobs/map_job.h"
#include "sim_cache.h"

using namespace roadslam;

namespace {

double rtePercent(const std::string& gt, const std::string& est) {
  const auto m = eval::associate(datasets::readTum(gt), datasets::readTum(est), 0.02);
  return eval::computeMetrics(m).rte_percent;
}

jobs::MapOutcome runTunnel(const std::string& sim_dir, const std::string& name, bool with_can,
                           const std::string& config = std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini") {
  jobs::MapRequest req;
  req.config_path = config;
  req.input_path = sim_dir + "/velodyne.pcap";
  req.out_dir = std::string(ROADSLAM_BINARY_DIR) + "/test-out/" + name;
  req.progress = false;
  if (with_can) {
    req.can_log_path = sim_dir + "/can.log";
    req.vehicle_ini_path = std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/roadslam-sim.ini";
  }
  return jobs::runMapJob(req);
}

/// ini/default.ini with {section, key, value} overrides, written into the build tree.
std::string defaultIniWith(const std::string& name, const std::vector<std::array<std::string, 3>>& overrides) {
  std::ifstream in(std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini");
  std::stringstream ss;
  ss << in.rdbuf();
  mrpt::config::CConfigFileMemory cfg;
  cfg.setContent(ss.str());
  for (const auto& [section, key, value] : overrides) cfg.write(section, key, value);
  const std::string path = std::string(ROADSLAM_BINARY_DIR) + "/test-out/" + name + ".ini";
  std::filesystem::create_directories(std::string(ROADSLAM_BINARY_DIR) + "/test-out");
  std::ofstream(path) << cfg.getContent();
  return path;
}

/// The tunnel drive driving off at once (no standstill to measure the gyro bias on) with a RAV4-like
/// CAN: yaw-rate bias -0.4 deg/s, wheel speeds 0.9 % short. 20 s to the portal, 20 s inside.
std::string biasedTunnel() {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/tunnel.ini");
  p.duration_s = 40;
  p.trajectory.start_standing_s = 0;
  p.can.yaw_rate_bias_radps = -0.4 * M_PI / 180;
  p.can.wheel_speed_scale_error = -0.009;
  return jobs::test::simulateOnce(p);
}

/// RTE [%] and ATE [m] of \p est over the frames stamped after \p t_from_s (the tunnel).
eval::TrajectoryMetrics metricsFrom(const std::string& gt, const std::string& est, double t_from_s) {
  auto m = eval::associate(datasets::readTum(gt), datasets::readTum(est), 0.02);
  eval::MatchedTrajectories tail;
  for (size_t i = 0; i < m.stamps_s.size(); ++i) {
    if (m.stamps_s[i] < t_from_s) continue;
    tail.gt.push_back(m.gt[i]);
    tail.est.push_back(m.est[i]);
    tail.stamps_s.push_back(m.stamps_s[i]);
  }
  return eval::computeMetrics(tail);
}

}  // namespace

// Online calibration of the wheel odometry against the LiDAR (oracle: the simulator's configured CAN
// errors), the tunnel's odometry with the calibrated prior against the uncalibrated one, and the
// corrected trajectory with [pose_graph] can_edges against the one without.
TEST(CanPrior, OnlineCalibrationAndCanEdgesOnTheBiasedTunnel) {
  const std::string dir = biasedTunnel();
  // a straight road: no loop to find, and no OctoMap needed (saves ~1/4 of each run)
  const std::array<std::string, 3> no_octomap{"octomap", "enabled", "false"}, no_loops{"loop_closure", "enabled", "false"};
  const auto cal = runTunnel(dir, "tunnel-biased-cal", true, defaultIniWith("biased-cal", {no_octomap, no_loops}));
  const auto raw = runTunnel(dir, "tunnel-biased-raw", true,
                             defaultIniWith("no-online-calibration",
                                            {no_octomap, no_loops, {"vehicle_prior", "online_calibration", "false"}}));
  const auto& c = cal.summary["can"]["calibration"];
  std::cout << "calibration: " << c.dump() << "\n";
  ASSERT_FALSE(c["online_yaw_rate_bias_deg_s"].is_null());
  ASSERT_FALSE(c["online_speed_scale"].is_null());
  EXPECT_NEAR(c["yaw_rate_bias_deg_s"].get<double>(), -0.4, 0.02);
  const double true_scale = 1 / (1 - 0.009);
  EXPECT_NEAR(c["speed_scale"].get<double>(), true_scale, 0.002 * true_scale);
  EXPECT_EQ(raw.summary["can"]["calibration"]["speed_scale"].get<double>(), 1.0);  // the control ran uncalibrated
  EXPECT_EQ(raw.summary["can"]["calibration"]["yaw_rate_bias_deg_s"].get<double>(), 0.0);
  // the frames inside the tunnel (from 21 s on: 250 m after accelerating at 1.5 m/s^2 to 60 km/h)
  const double t_portal = 1700000000.0 + 21.0;
  const std::string gt = dir + "/gt_trajectory.tum", out = std::string(ROADSLAM_BINARY_DIR) + "/test-out/";
  const auto m_cal = metricsFrom(gt, out + "tunnel-biased-cal/trajectory_odometry.tum", t_portal);
  const auto m_raw = metricsFrom(gt, out + "tunnel-biased-raw/trajectory_odometry.tum", t_portal);
  std::cout << "tunnel part: calibrated prior RTE " << m_cal.rte_percent << " % ATE " << m_cal.ate_rmse_m
            << " m; uncalibrated RTE " << m_raw.rte_percent << " % ATE " << m_raw.ate_rmse_m << " m (path "
            << m_cal.path_length_m << " m)\n";
  EXPECT_GT(m_cal.path_length_m, 250.0);
  EXPECT_LT(m_cal.rte_percent, m_raw.rte_percent);
  EXPECT_LT(m_cal.ate_rmse_m, m_raw.ate_rmse_m);

  // [pose_graph] can_edges on the same drive: the wheels join the keyframe edges, the corrected
  // trajectory (trajectory.tum) follows them where the scans were degenerate
  const auto edges = runTunnel(dir, "tunnel-biased-edges", true,
                               defaultIniWith("can-edges", {no_octomap, no_loops, {"pose_graph", "can_edges", "true"},
                                                            {"pose_graph", "isotropic_weak_ratio", "0.01"}}));
  EXPECT_GT(edges.summary["can_edges"].get<int>(), 200);
  EXPECT_EQ(cal.summary["can_edges"].get<int>(), 0);
  const auto e_cal = metricsFrom(gt, out + "tunnel-biased-cal/trajectory.tum", 0);
  const auto e_edges = metricsFrom(gt, out + "tunnel-biased-edges/trajectory.tum", 0);
  std::cout << "whole drive, corrected trajectory: ATE " << e_edges.ate_rmse_m << " m with CAN edges, "
            << e_cal.ate_rmse_m << " m without\n";
  // With the gravity prior the calibrated odometry alone holds this drive (0.18 m ATE; 1.26 m before
  // it), so the edges have little left to correct (measured 0.19 m): they must not make it worse. Their
  // effect where the lidar is degenerate and the odometry drifts: MapperSim.CanEdgesHoldTheTunnel...
  EXPECT_LT(e_edges.ate_rmse_m, 0.3);
  EXPECT_LT(e_edges.ate_rmse_m, 1.15 * e_cal.ate_rmse_m);
}

TEST(CanPrior, TunnelHoldsWithTheWheelOdometryPrior) {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/tunnel.ini");
  p.duration_s = 30;
  const std::string dir = jobs::test::simulateOnce(p);
  const auto with = runTunnel(dir, "tunnel-can", true);
  const auto without = runTunnel(dir, "tunnel-nocan", false);
  EXPECT_EQ(with.summary["can"]["priors_missing"].get<int>(), 0);
  EXPECT_GT(with.summary["can"]["priors_used"].get<int>(), 250);
  const std::string gt = dir + "/gt_trajectory.tum";
  const double rte_with = rtePercent(gt, std::string(ROADSLAM_BINARY_DIR) + "/test-out/tunnel-can/trajectory_odometry.tum");
  const double rte_without =
      rtePercent(gt, std::string(ROADSLAM_BINARY_DIR) + "/test-out/tunnel-nocan/trajectory_odometry.tum");
  std::cout << "tunnel 30 s: RTE " << rte_with << " % with the CAN prior, " << rte_without << " % without\n";
  EXPECT_LT(rte_with, 0.5);  // measured 0.12 %
  // the control: without the prior the corridor is barely measurable along its axis (2.3 % measured)
  EXPECT_GT(rte_without, 5 * rte_with);
}

TEST(CanPrior, CanLogWithoutVehicleIniIsRefused) {
  jobs::MapRequest req;
  req.config_path = std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini";
  req.input_path = std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap";
  req.out_dir = std::string(ROADSLAM_BINARY_DIR) + "/test-out/can-no-vehicle";
  req.can_log_path = "/nonexistent.log";
  EXPECT_THROW(jobs::runMapJob(req), std::runtime_error);
}
