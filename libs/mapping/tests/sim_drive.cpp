#include <filesystem>
#include "sim_drive.h"

#include <cmath>

#include "roadslam/eval/trajectory_metrics.h"
#include "roadslam/odometry/deskew.h"
#include "roadslam/registration/point_cloud.h"
#include "roadslam/sim/eigen.h"
#include "roadslam/sim/sweep_sink.h"
#include "roadslam/velodyne/packet.h"

namespace roadslam::mapping::test {
namespace {

using sim::toEigen;

}  // namespace

std::vector<SimFrame> simulateDrive(const sim::ScenarioParams& p, const DriftModel& drift, Eigen::Isometry3d* T_sim_world) {
  sim::Simulator s(p);
  std::vector<Scan> sweeps;
  sim::SweepSink sink([&](Scan&& sc) { sweeps.push_back(std::move(sc)); });
  s.run(sink);
  std::vector<SimFrame> out;
  Eigen::Isometry3d T_gt0 = Eigen::Isometry3d::Identity(), T_prev_gt = T_gt0, T_drift = T_gt0, T_kf = T_gt0;
  for (size_t k = 0; k < sweeps.size(); ++k) {
    const Scan& sc = sweeps[k];
    const double t0 = sc.stamp_s - static_cast<double>(p.start_epoch_s);
    const Eigen::Isometry3d T_gt = toEigen(s.lidar().lidarPose(t0));
    if (k == 0) T_gt0 = T_gt;
    if (k == 0 && T_sim_world) *T_sim_world = T_gt;
    SimFrame f;
    f.T_world_lidar_gt = T_gt0.inverse() * T_gt;
    // drifted odometry: true increment, scaled, with a heading error proportional to the distance
    Eigen::Isometry3d d = k == 0 ? Eigen::Isometry3d::Identity() : T_prev_gt.inverse() * f.T_world_lidar_gt;
    const double step = d.translation().norm();
    d.translation() *= drift.scale;
    d.linear() = Eigen::AngleAxisd(drift.yaw_rad_per_m * step, Eigen::Vector3d::UnitZ()) * d.linear();
    T_drift = T_drift * d;
    T_prev_gt = f.T_world_lidar_gt;
    f.result.index = k;
    f.result.stamp_s = sc.stamp_s;
    f.result.T_world_lidar = T_drift;
    f.result.status = k == 0 ? odometry::FrameStatus::First : odometry::FrameStatus::Ok;
    f.result.keyframe = k == 0 || (T_kf.inverse() * T_drift).translation().norm() >= drift.keyframe_m;
    if (f.result.keyframe) T_kf = T_drift;
    // rotation ~100x stiffer than translation, like a scan registration (lever arms of ~10 m)
    // (about the lidar; the odometry reports it about its world frame, as registration does)
    Eigen::Matrix<double, 6, 6> I_lidar = Eigen::Matrix<double, 6, 6>::Zero();
    I_lidar.diagonal() << 1e4, 1e4, 1e4, 1e6, 1e6, 1e6;
    f.result.information = sourceFrameInformation(I_lidar, T_drift.inverse());
    const Eigen::Isometry3d T_start_end = toEigen(s.lidar().lidarPose(t0)).inverse() * toEigen(s.lidar().lidarPose(t0 + 0.1));
    f.points_lidar = registration::voxelDownsample(odometry::deskew(sc, T_start_end, 0.1), 0.25);
    out.push_back(std::move(f));
  }
  return out;
}

double ateRmse(const PoseVector& gt, const PoseVector& est) {
  eval::MatchedTrajectories m;
  m.gt.assign(gt.begin(), gt.end());
  m.est.assign(est.begin(), est.end());
  m.stamps_s.resize(gt.size());
  for (size_t i = 0; i < gt.size(); ++i) m.stamps_s[i] = static_cast<double>(i);
  return eval::computeMetrics(m).ate_rmse_m;
}

MapFolder gtMapFolder(const std::vector<SimFrame>& frames, size_t end, const std::string& dir) {
  std::vector<Keyframe> kfs;
  PoseVector T_map_kf;
  double path = 0;
  for (size_t i = 0; i < end; ++i) {
    if (i > 0) path += (frames[i].T_world_lidar_gt.translation() - frames[i - 1].T_world_lidar_gt.translation()).norm();
    if (!kfs.empty() && path - kfs.back().path_m < 2.0) continue;
    Keyframe k;
    k.frame_index = i;
    k.path_m = path;
    for (const auto& q : registration::voxelDownsample(frames[i].points_lidar, 0.3)) k.points_lidar.push_back(q.cast<float>());
    kfs.push_back(std::move(k));
    T_map_kf.push_back(frames[i].T_world_lidar_gt);
  }
  std::filesystem::create_directories(dir);
  writeMapFolder(dir, kfs, T_map_kf, place::ScanContextParams{});
  return readMapFolder(dir);
}

}  // namespace roadslam::mapping::test
