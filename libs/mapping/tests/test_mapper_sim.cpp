// Loop closure against the simulator's ground truth: frames carry a known odometry drift (heading
// error per metre and a scale error); the mapper must find the loop, reject look-alikes, and bring
// the keyframe trajectory back to the truth.
#include <gtest/gtest.h>

#include <iostream>

#include "roadslam/mapping/mapper.h"
#include "sim_drive.h"

using namespace roadslam;
using namespace roadslam::mapping;

namespace {

struct RunResult {
  double ate_odometry_m = 0, ate_corrected_m = 0;
  size_t accepted = 0, rejected = 0;
  double worst_loop_error_m = 0;  ///< accepted loop measurement vs the true relative pose [m]
};

RunResult runMapper(const std::vector<test::SimFrame>& frames, const MapperParams& mp) {
  Mapper mapper(mp);
  for (const auto& f : frames) mapper.addFrame(f.result, f.points_lidar);
  const auto T_map_kf = mapper.keyframePoses();
  PoseVector gt, odo, cor;
  for (const auto& f : frames) {
    gt.push_back(f.T_world_lidar_gt);
    odo.push_back(f.result.T_world_lidar);
    cor.push_back(mapper.correctedPose(f.result, T_map_kf));
  }
  RunResult r;
  r.ate_odometry_m = test::ateRmse(gt, odo);
  r.ate_corrected_m = test::ateRmse(gt, cor);
  if (getenv("MAPPING_DEBUG")) {
    for (size_t i = 0; i < gt.size(); i += 20) {
      std::cout << i << " err_cor " << (gt[i].translation() - cor[i].translation()).norm() << " err_odo "
                << (gt[i].translation() - odo[i].translation()).norm() << " yaw_err_cor "
                << Eigen::AngleAxisd(gt[i].rotation().transpose() * cor[i].rotation()).angle() << "\n";
    }
  }
  for (const auto& l : mapper.loopResults()) {
    (l.accepted ? r.accepted : r.rejected)++;
    std::cout << "  loop kf " << l.query << " -> " << l.match << ": " << l.reason << " fitness " << l.fitness_m
              << " overlap " << l.overlap << " correction " << l.correction_m << " m " << l.ms << " ms\n";
    if (!l.accepted) continue;
    const auto& kq = mapper.keyframes()[l.query];
    const auto& km = mapper.keyframes()[l.match];
    const Eigen::Isometry3d T_true = frames[km.frame_index].T_world_lidar_gt.inverse() * frames[kq.frame_index].T_world_lidar_gt;
    r.worst_loop_error_m = std::max(r.worst_loop_error_m, (T_true.inverse() * l.T_match_query).translation().norm());
  }
  std::cout << "ATE odometry " << r.ate_odometry_m << " m, after loop closure " << r.ate_corrected_m
            << " m; loops accepted " << r.accepted << ", rejected " << r.rejected
            << ", worst accepted loop error " << r.worst_loop_error_m << " m\n";
  return r;
}

sim::ScenarioParams smallLoop() {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
  p.world.length_m = 110;
  p.world.width_m = 70;
  p.world.moving_cars = 2;
  p.trajectory.start_standing_s = 0.5;
  return p;
}

}  // namespace

TEST(MapperSim, SmallUrbanLoopIsClosed) {
  const auto frames = test::simulateDrive(smallLoop(), test::DriftModel{});
  ASSERT_GT(frames.size(), 200u);
  const auto r = runMapper(frames, MapperParams{});
  EXPECT_GE(r.accepted, 1u);
  EXPECT_LT(r.worst_loop_error_m, 0.3);
  EXPECT_LE(r.ate_corrected_m, 0.20);
  EXPECT_LE(3 * r.ate_corrected_m, r.ate_odometry_m);
}

TEST(MapperSim, LoopClosureDisabledKeepsOdometry) {
  auto p = smallLoop();
  p.duration_s = 8;
  const auto frames = test::simulateDrive(p, test::DriftModel{});
  MapperParams mp;
  mp.loop.enabled = false;
  Mapper mapper(mp);
  for (const auto& f : frames) mapper.addFrame(f.result, f.points_lidar);
  const auto T_map_kf = mapper.keyframePoses();
  EXPECT_EQ(mapper.loopResults().size(), 0u);
  for (const auto& f : frames) {
    EXPECT_LT((mapper.correctedPose(f.result, T_map_kf).translation() - f.result.T_world_lidar.translation()).norm(), 1e-6);
  }
}

TEST(MapperSim, ParallelStreetsNoFalseLoop) {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/parallel-streets.ini");
  p.world.length_m = 120;
  p.world.width_m = 40;
  p.world.moving_cars = 2;
  p.trajectory.start_standing_s = 0.5;
  const auto frames = test::simulateDrive(p, test::DriftModel{});
  const auto r = runMapper(frames, MapperParams{});
  // every accepted loop must be a true revisit (its measurement agrees with the truth)
  EXPECT_LT(r.worst_loop_error_m, 0.3);
  EXPECT_LE(r.ate_corrected_m, r.ate_odometry_m + 0.05);
}
