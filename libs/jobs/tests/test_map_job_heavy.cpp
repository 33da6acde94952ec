// Heavy end-to-end runs of roadslam-map's job (minutes): the whole urban loop (~1 km; the odometry's
// and the loop closure's targets) and the parallel streets (look-alike places), against the
// simulator's ground truth.
#include <gtest/gtest.h>

#include <iostream>

#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/eval/evaluate.h"
#include "roadslam/jobs/map_job.h"
#include "sim_cache.h"

using namespace roadslam;

namespace {

jobs::MapOutcome run(const std::string& sim_dir, const std::string& name) {
  jobs::MapRequest req;
  req.config_path = std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini";
  req.input_path = sim_dir + "/velodyne.pcap";
  req.out_dir = std::string(ROADSLAM_BINARY_DIR) + "/test-out/" + name;
  req.progress = false;
  return jobs::runMapJob(req);
}

eval::TrajectoryMetrics metrics(const std::string& gt, const std::string& est) {
  eval::EvalRequest req;
  req.gt_path = gt;
  req.est_path = est;
  return eval::evaluate(req).metrics;
}

double ate(const std::string& gt, const std::string& est) { return metrics(gt, est).ate_rmse_m; }

Eigen::Vector3d gtPositionAt(const datasets::Trajectory& gt, double t) {
  size_t best = 0;
  for (size_t i = 1; i < gt.stamps_s.size(); ++i) {
    if (std::abs(gt.stamps_s[i] - t) < std::abs(gt.stamps_s[best] - t)) best = i;
  }
  return gt.poses[best].translation();
}

}  // namespace

TEST(MapJobHeavy, FullUrbanLoop) {
  const auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
  const std::string sim_dir = jobs::test::simulateOnce(p);
  const auto out = run(sim_dir, "map-job-urban-loop");
  const std::string dir = std::string(ROADSLAM_BINARY_DIR) + "/test-out/map-job-urban-loop";
  const auto odo = metrics(sim_dir + "/gt_trajectory.tum", dir + "/trajectory_odometry.tum");
  const double ate_slam = ate(sim_dir + "/gt_trajectory.tum", dir + "/trajectory.tum");
  std::cout << "urban loop: ATE odometry " << odo.ate_rmse_m << " m, with loop closure " << ate_slam << " m, loops "
            << out.summary["loop_closures"] << "; odometry path " << odo.path_length_m << " m, RTE "
            << odo.rte_percent << " %, RRE " << odo.rre_deg_per_100m << " deg/100 m\n";
  EXPECT_GE(out.summary["loop_closures"].get<int>(), 1);
  // The loop closure's target: <= 0.20 m and well below the odometry. The odometry alone is at
  // ~0.11 m on the whole loop and the loop closure halves it (3x below it is out of reach at that accuracy).
  EXPECT_LE(ate_slam, 0.20);
  EXPECT_LE(1.5 * ate_slam, odo.ate_rmse_m);
  // The odometry alone (ini/default.ini, no CAN) on the whole loop within its target: RTE < 0.5 %
  // (measured 0.070 %), ATE < 0.5 m, every sweep registered. Checked on this job's own odometry
  // trajectory rather than by a second run of the same odometry over the same loop.
  EXPECT_GT(odo.path_length_m, 950.0);
  EXPECT_LT(odo.rte_percent, 0.5);
  EXPECT_LT(odo.ate_rmse_m, 0.5);
  const auto& by_status = out.summary["frames_by_status"];
  EXPECT_EQ(by_status.value("not_converged", 0) + by_status.value("empty", 0), 0) << by_status.dump();
}

TEST(MapJobHeavy, ParallelStreetsNoFalseLoop) {
  const auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/parallel-streets.ini");
  const std::string sim_dir = jobs::test::simulateOnce(p);
  const auto out = run(sim_dir, "map-job-parallel-streets");
  const auto gt = datasets::readTum(sim_dir + "/gt_trajectory.tum");
  // a true revisit: the two frames are within the candidate radius in the truth (streets are 60 m apart)
  for (const auto& l : out.summary["loops"]["accepted"]) {
    const double tq = out.frames.at(l["query_frame"].get<size_t>()).stamp_s;
    const double tm = out.frames.at(l["match_frame"].get<size_t>()).stamp_s;
    const double d = (gtPositionAt(gt, tq) - gtPositionAt(gt, tm)).norm();
    std::cout << "accepted loop frames " << l["query_frame"] << " -> " << l["match_frame"] << ": true distance " << d
              << " m\n";
    EXPECT_LT(d, 12.0) << "false loop accepted";
  }
}

// roadslam-map --prior-map, wiring end to end: a map folder made by a first run over the small
// loop, then the same recording localized in it (an unknown start: the first sweep is relocalized). The
// accuracy on a second, different lap is MapperSim.SecondLapByPlaceRecognition's; here every sweep must get
// a pose in the map and the trajectory must match the truth.
TEST(MapJobHeavy, LocalizesInAPriorMap) {
  const std::string sim_dir = jobs::test::simulateOnce(jobs::test::smallLoop());
  run(sim_dir, "map-job-prior-map-a");
  const std::string map_dir = std::string(ROADSLAM_BINARY_DIR) + "/test-out/map-job-prior-map-a";
  jobs::MapRequest req;
  req.config_path = std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini";
  req.input_path = sim_dir + "/velodyne.pcap";
  req.out_dir = std::string(ROADSLAM_BINARY_DIR) + "/test-out/map-job-prior-map-b";
  req.progress = false;
  req.prior_map_dir = map_dir;
  const auto out = jobs::runMapJob(req);
  const auto& loc = out.summary["localization"];
  std::cout << "prior map: " << loc.dump() << "\n";
  EXPECT_GE(loc["relocalized"].get<int>(), 1);
  EXPECT_LE(loc["lost"].get<int>(), 2);
  EXPECT_FALSE(out.summary.contains("loop_closures")) << "the prior map is not grown";
  const double ate_loc = ate(sim_dir + "/gt_trajectory.tum", req.out_dir + "/trajectory.tum");
  std::cout << "prior map: ATE " << ate_loc << " m\n";
  EXPECT_LE(ate_loc, 0.10);
  // an older folder (no map.json) is refused naming the file
  req.prior_map_dir = sim_dir;
  try {
    jobs::runMapJob(req);
    ADD_FAILURE() << "a folder without map.json was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("map.json"), std::string::npos) << e.what();
  }
}
