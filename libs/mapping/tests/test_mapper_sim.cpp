// Loop closure against the simulator's ground truth: frames carry a known odometry drift (heading
// error per metre and a scale error); the mapper must find the loop, reject look-alikes, and bring
// the keyframe trajectory back to the truth.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "roadslam/localization/localizer.h"
#include "roadslam/mapping/mapper.h"
#include "roadslam/pipeline/vehicle_prior.h"
#include "roadslam/sim/can_output.h"
#include "roadslam/sim/eigen.h"
#include "roadslam/vehicle/params.h"
#include "sim_drive.h"

using namespace roadslam;
using namespace roadslam::localization;
using namespace roadslam::mapping;

namespace {

struct RunResult {
  double ate_odometry_m = 0, ate_corrected_m = 0;
  size_t accepted = 0, rejected = 0;
  double worst_loop_error_m = 0;  ///< accepted loop measurement vs the true relative pose [m]
};

RunResult runMapper(const std::vector<test::SimFrame>& frames, const MapperParams& mp_in) {
  MapperParams mp = mp_in;
  if (getenv("POSE_GRAPH_MRPT")) mp.graph.optimizer = GraphOptimizer::MrptLevmarq;  // the old optimiser, to compare
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
    if (getenv("MAPPING_DEBUG") && l.reason == "graph residual") {
      const auto& kq = mapper.keyframes()[l.query];
      const auto& km = mapper.keyframes()[l.match];
      const Eigen::Isometry3d T_true = frames[km.frame_index].T_world_lidar_gt.inverse() * frames[kq.frame_index].T_world_lidar_gt;
      std::cout << "    rejected loop error vs GT " << (T_true.inverse() * l.T_match_query).translation().norm() << " m\n";
    }
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
  // Scan Context candidates on the same drive: it offers the look-alike streets 40 m apart and
  // global registration matches them (one 54 m off was accepted before the place_consistency test); no
  // false loop enters the graph, the true revisit at the end does.
  MapperParams sc;
  sc.loop.candidates = LoopCandidates::ScanContext;
  const auto rs = runMapper(frames, sc);
  EXPECT_GE(rs.accepted, 1u);
  EXPECT_LT(rs.worst_loop_error_m, 0.3);
  EXPECT_LE(2 * rs.ate_corrected_m, rs.ate_odometry_m);
}

// Place recognition: the small loop driven 1.4 times with a heading drift of 0.03 deg/m (the
// second lap starts ~11 m off in the graph): Scan Context candidates, verified by global registration,
// close the loop and every accepted loop agrees with the truth, at the loops' full information (MRPT's
// optimiser, POSE_GRAPH_MRPT=1, left the graph 4.5 m off these exact loops and the residual test rejected
// all 69 of them: it needed place_information_scale = 0.01).
//
// Then localization (Localizer) on the same drive's second lap in a map folder of the first lap made at the
// true poses (written and read back): an unknown start and a kidnapping (4 s of sweeps skipped while
// tracking) are relocalized at once; every pose is checked against the truth directly (the map's frame is
// the world's).
TEST(MapperSim, SecondLapByPlaceRecognition) {
  auto p = smallLoop();
  p.trajectory.laps = 2;
  p.duration_s = 58;  // ~1.4 laps of ~42 s
  test::DriftModel drift;
  drift.yaw_rad_per_m = 0.03 * M_PI / 180;
  const auto frames = test::simulateDrive(p, drift);
  MapperParams sc;
  sc.loop.candidates = LoopCandidates::ScanContext;
  const auto r = runMapper(frames, sc);
  EXPECT_GE(r.accepted, 3u);
  EXPECT_LT(r.worst_loop_error_m, 0.3);
  EXPECT_LE(5 * r.ate_corrected_m, r.ate_odometry_m);

  // the first lap's map at the true poses
  double path = 0;
  size_t lap2 = 0;
  for (size_t i = 1; i < frames.size() && lap2 == 0; ++i) {
    path += (frames[i].T_world_lidar_gt.translation() - frames[i - 1].T_world_lidar_gt.translation()).norm();
    if (path > 100 && (frames[i].T_world_lidar_gt.translation() - frames[0].T_world_lidar_gt.translation()).norm() < 1.0)
      lap2 = i;  // back at the start: one lap mapped
  }
  ASSERT_GT(lap2, 0u);
  Localizer loc(gtMapFolder(frames, lap2, std::string(ROADSLAM_BINARY_DIR) + "/test-out-localizer-map"));
  int lost = 0, relocalized = 0, n = 0;
  double ms_track = 0, ms_reloc = 0;  // printed only (speed belongs to benchmarks)
  double sum_e2 = 0, worst = 0;
  for (size_t i = lap2 + 5; i < frames.size(); ++i) {
    if (i == lap2 + 25) i += 40;  // kidnapped: 4 s of sweeps never seen (~30 m), no reset
    if (i >= frames.size()) break;
    const auto t0 = std::chrono::steady_clock::now();
    const LocalizationResult l = loc.localize(frames[i].points_lidar);
    (l.status == LocalizationStatus::Tracked ? ms_track : ms_reloc) +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (getenv("MAPPING_DEBUG"))
      std::cout << "  sweep " << i << ": " << toString(l.status) << " conf " << l.confidence << " " << l.reason << " weak " << l.weak_directions << " err "
                << (l.T_map_lidar.translation() - frames[i].T_world_lidar_gt.translation()).norm() << "\n";
    if (l.status == LocalizationStatus::Lost) {
      ++lost;
      continue;
    }
    relocalized += l.status == LocalizationStatus::Relocalized ? 1 : 0;
    const double e = (l.T_map_lidar.translation() - frames[i].T_world_lidar_gt.translation()).norm();
    sum_e2 += e * e;
    worst = std::max(worst, e);
    ++n;
  }
  const double ate = n > 0 ? std::sqrt(sum_e2 / n) : 1e9;
  std::cout << "localization: " << n << " sweeps localized, " << lost << " lost, " << relocalized << " relocalizations, ATE "
            << ate << " m, worst " << worst << " m, map points " << loc.mapPoints() << "; wall ms per tracked sweep "
            << ms_track / std::max(1, n - relocalized) << ", per relocalization " << ms_reloc / std::max(1, relocalized + lost) << "\n";
  EXPECT_LE(lost, 10) << "relocalized within 1 s, twice";
  EXPECT_LE(relocalized, 3);  // the start and the kidnapping
  EXPECT_GE(relocalized, 2);
  EXPECT_LE(ate, 0.10);
  EXPECT_LE(worst, 0.3);
}


namespace {

/// The tunnel drive at 10 Hz without raycasting: odometry = true increments, except inside the tube
/// (250-750 m along the road) where a degenerate registration (no prior) keeps only 70 % of the
/// along-road motion and says so in its information (weak along lidar x); the CAN motion of every
/// frame from the simulator's CAN log (bias, scale error, noise), decoded and dead reckoned.
struct TunnelFrames {
  std::vector<odometry::FrameResult> odo;
  std::vector<std::optional<WheelMotion>> wheel;
  PoseVector gt;
  size_t degenerate = 0;
};

TunnelFrames tunnelFrames(double duration_s) {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/tunnel.ini");
  p.duration_s = duration_s;
  sim::Simulator s(p);
  const auto vp = vehicle::loadVehicleIni(std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/roadslam-sim.ini");
  vehicle::VehicleDecoder dec(vp);
  pipeline::VehiclePriorParams pp;
  pp.T_base_lidar = sim::toEigen(s.lidar().vehicleToLidar());
  pp.history_s = duration_s + 1;
  pipeline::VehiclePrior prior(pp, vp);
  vehicle::VehicleState state;
  const double t0 = static_cast<double>(p.start_epoch_s);
  for (const auto& f : sim::simulateCan(s, duration_s)) prior.update(state, dec.process(f, state));
  TunnelFrames out;
  const Eigen::Isometry3d T_gt0 = sim::toEigen(s.lidar().lidarPose(0.0));
  Eigen::Isometry3d T_odo = Eigen::Isometry3d::Identity(), T_kf = T_odo;
  for (size_t k = 0; 0.1 * static_cast<double>(k) <= duration_s - 0.1; ++k) {
    const double t = 0.1 * static_cast<double>(k);
    out.gt.push_back(T_gt0.inverse() * sim::toEigen(s.lidar().lidarPose(t)));
    odometry::FrameResult f;
    f.index = k;
    f.stamp_s = t0 + t;
    f.status = k == 0 ? odometry::FrameStatus::First : odometry::FrameStatus::Ok;
    f.information.diagonal() << 1e4, 1e4, 1e4, 1e6, 1e6, 1e6;
    std::optional<WheelMotion> wheel;
    if (k > 0) {
      Eigen::Isometry3d d = out.gt[k - 1].inverse() * out.gt[k];
      const double s_m = s.trajectory().at(t).s_m;
      if (s_m > 250 && s_m < 750) {
        d.translation().x() *= 0.7;
        f.status = odometry::FrameStatus::NotConverged;
        f.information(0, 0) = 1e-2;
        ++out.degenerate;
      }
      T_odo = T_odo * d;
      if (const auto T_b = prior.baseMotion(t0 + t - 0.1, t0 + t)) wheel = WheelMotion{*T_b, pp.T_base_lidar};
    }
    f.T_world_lidar = T_odo;
    f.information = sourceFrameInformation(f.information, T_odo.inverse());  // about the world frame, as the odometry's
    f.keyframe = k == 0 || (T_kf.inverse() * T_odo).translation().norm() >= 1.0;
    if (f.keyframe) T_kf = T_odo;
    out.odo.push_back(f);
    out.wheel.push_back(wheel);
  }
  return out;
}

double runTunnelMapper(const TunnelFrames& tf, const MapperParams& mp, Mapper* keep = nullptr) {
  Mapper local(mp);
  Mapper& mapper = keep ? *keep : local;
  const std::vector<Eigen::Vector3d> no_points;
  for (size_t k = 0; k < tf.odo.size(); ++k) mapper.addFrame(tf.odo[k], no_points, tf.wheel[k]);
  const auto T_map_kf = mapper.keyframePoses();
  PoseVector cor;
  for (const auto& f : tf.odo) cor.push_back(mapper.correctedPose(f, T_map_kf));
  return test::ateRmse(tf.gt, cor);
}

}  // namespace

TEST(MapperSim, CanEdgesHoldTheTunnelWhereTheLidarIsDegenerate) {
  const TunnelFrames tf = tunnelFrames(45.0);
  ASSERT_GT(tf.degenerate, 100u);
  MapperParams off;
  off.loop.enabled = false;
  off.graph.isotropic_weak_ratio = 0.01;  // the tunnel's unmeasured axis stays weak in the odometry edges
  MapperParams on = off;
  on.graph.can_edges = true;
  Mapper with(on);
  const double ate_off = runTunnelMapper(tf, off);
  const double ate_on = runTunnelMapper(tf, on, &with);
  MapperParams on_mean = on;  // for the record: the plain isotropic mean hides the weak axis
  on_mean.graph.isotropic_weak_ratio = 0;
  const double ate_on_mean = runTunnelMapper(tf, on_mean);
  std::cout << "tunnel 45 s (" << tf.degenerate << " degenerate frames): ATE without CAN edges " << ate_off
            << " m, with " << ate_on << " m (" << with.canEdges() << " CAN edges; " << ate_on_mean
            << " m with isotropic_weak_ratio 0)\n";
  // every keyframe pair had the CAN motion but the first (the CAN log starts after the first sweep)
  EXPECT_GE(with.canEdges() + 2, with.keyframes().size());
  EXPECT_EQ(with.graph().numEdges(), with.keyframes().size() - 1);  // fused: one edge per keyframe pair
  EXPECT_LT(ate_on, 0.1 * ate_off);
  // the graph file holds one EDGE3 line per keyframe pair, the fused CAN + odometry measurement
  const std::string path = std::string(ROADSLAM_BINARY_DIR) + "/test-out-can-edges.graph";
  with.graph().saveToTextFile(path);
  std::ifstream in(path);
  size_t edge3 = 0;
  for (std::string line; std::getline(in, line);) edge3 += line.rfind("EDGE3", 0) == 0;
  EXPECT_EQ(edge3, with.keyframes().size() - 1);
}
