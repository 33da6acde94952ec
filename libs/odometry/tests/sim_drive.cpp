#include "sim_drive.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

#include "roadslam/common/config.h"
#include "roadslam/can/frame.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/sim/eigen.h"
#include "roadslam/sim/sweep_sink.h"
#include "roadslam/vehicle/vehicle_state.h"

namespace roadslam::odometry::test {
namespace {

using sim::toEigen;

/// The simulated CAN stream fed up to each sweep's time into the vehicle prior.
struct CanFeed {
  std::vector<can::CanFrame> frames;
  size_t next = 0;
  vehicle::VehicleDecoder decoder;
  vehicle::VehicleState state;
  pipeline::VehiclePrior prior;
  CanFeed(const sim::Simulator& s, double duration_s, const vehicle::VehicleParams& vp, const pipeline::VehiclePriorParams& pp)
      : frames(sim::simulateCan(s, duration_s)), decoder(vp), prior(pp, vp) {}
  void feedUntil(double t_s) {
    for (; next < frames.size() && frames[next].timeSeconds() <= t_s; ++next)
      prior.update(state, decoder.process(frames[next], state));
  }
};

struct OdometryRun {
  OdometryRun(const sim::Simulator& s, const Params& p) : sim(s), odo(p) {}
  const sim::Simulator& sim;
  Odometry odo;
  sim::SweepSink sink{[this](Scan&& scan) { process(std::move(scan)); }};
  std::unique_ptr<CanFeed> can;
  double last_pose_stamp_s = -1;
  eval::MatchedTrajectories m;
  SimDriveResult r;
  double ms_sum = 0;
  std::function<void(const FrameResult&, const Odometry&)> on_frame;

  void process(Scan scan) {
    if (scan.partial) return;
    std::optional<MotionPrior> prior;
    const double scan_stamp_s = scan.stamp_s;
    if (can) {
      can->feedUntil(scan_stamp_s + odo.params().sweep_duration_s);  // CAN received while the sweep lasted
      if (last_pose_stamp_s > 0) prior = can->prior.between(last_pose_stamp_s, odo.poseTimeOf(scan));
      r.with_prior += prior.has_value();
    }
    const auto f = odo.process(std::move(scan), prior);
    if (f.status == FrameStatus::Skipped) return;
    last_pose_stamp_s = f.stamp_s;
    ++r.frames;
    r.failed += f.status == FrameStatus::NotConverged || f.status == FrameStatus::Empty;
    r.degenerate += f.status == FrameStatus::Degenerate;
    ms_sum += f.ms_total;
    const double t = f.stamp_s - static_cast<double>(sim.params().start_epoch_s);
    if (std::getenv("SIMDRIVE_VERBOSE")) {
      const Eigen::Isometry3d G = toEigen(sim.lidar().lidarPose(t));
      const Eigen::Vector3d g = G.translation(), e = f.T_world_lidar.translation();
      // Tilt of the lidar's z axis: [deg] about world x (roll-like) and y (pitch-like).
      const auto tilt = [](const Eigen::Isometry3d& T) -> Eigen::Vector2d {
        const Eigen::Vector3d z = T.linear().col(2);
        return Eigen::Vector2d(std::atan2(-z.y(), z.z()), std::atan2(z.x(), z.z())) * 180.0 / M_PI;
      };
      const Eigen::Vector2d te = tilt(f.T_world_lidar), tg = tilt(G);
      std::printf("%zu %s vc=%d it=%d inl=%d/%d fit=%.3f thr=%.2f weak=%d ev=%.4f mi=%.4f est=(%.2f %.2f %.2f) gt=(%.2f %.2f %.2f) "
                  "tilt_est=(%.3f %.3f) tilt_gt=(%.3f %.3f) %s\n", f.index,
                  toString(f.status), f.vertical_constraints, f.iterations, f.inliers, f.points_registered, f.fitness_m, f.threshold_m,
                  f.weak_directions, f.min_eigenvalue, f.motion_information, e.x(), e.y(), e.z(), g.x(), g.y(), g.z(), te.x(), te.y(),
                  tg.x(), tg.y(), f.reason.c_str());
    }
    m.gt.push_back(toEigen(sim.lidar().lidarPose(t)));
    r.statuses.push_back(f.status);
    r.gt_positions.push_back(m.gt.back().translation());
    m.est.push_back(f.T_world_lidar);
    m.stamps_s.push_back(f.stamp_s);
    if (on_frame) on_frame(f, odo);
  }
};

}  // namespace

SimDriveResult runSimDrive(const std::string& scenario_ini, double duration_s, const Params& params) {
  return runSimDrive(scenario_ini, duration_s, params, SimDriveOptions{});
}

SimDriveResult runSimDrive(const std::string& scenario_ini, double duration_s, const Params& params,
                           const SimDriveOptions& options) {
  auto sp = sim::ScenarioParams::fromFile(scenario_ini);
  sp.duration_s = duration_s;
  if (options.laps > 0) sp.trajectory.laps = options.laps;
  if (options.edit_scenario) options.edit_scenario(sp);
  sim::Simulator s(sp);
  OdometryRun run(s, params);
  run.on_frame = options.on_frame;
  if (options.can_prior) {
    pipeline::VehiclePriorParams pp = options.prior;
    pp.T_base_lidar = toEigen(s.lidar().vehicleToLidar());
    const auto vp = vehicle::loadVehicleIni(std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/roadslam-sim.ini");
    run.can = std::make_unique<CanFeed>(s, s.duration_s(), vp, pp);
  }
  s.run(run.sink);
  run.r.ms_mean = run.r.frames ? run.ms_sum / run.r.frames : 0;
  run.r.metrics = eval::computeMetrics(run.m);
  return run.r;
}

Params paramsFromIni(const std::string& path) {
  Params p;
  p.loadFromConfigFile(*loadIniFile(path));
  return p;
}

}  // namespace roadslam::odometry::test
