#include "roadslam/pipeline/pose_stage.h"

#include <algorithm>
#include <stdexcept>

#include "roadslam/common/pose_interpolation.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/odometry/deskew.h"
#include "roadslam/pipeline/can_prior.h"

namespace roadslam::pipeline {
namespace {

double sweepDuration(const Scan& s) {
  double d = 0;
  for (const auto& q : s.points) d = std::max<double>(d, q.t);
  return d;
}

bool converged(odometry::FrameStatus s) { return s == odometry::FrameStatus::Ok; }

}  // namespace

bool deskewToReference(Scan& scan, const SweepPose& pose) {
  if (!pose.ok || !pose.deskew) return false;
  odometry::deskewBetween(scan, pose.start, pose.end, pose.dur, pose.ref);
  return scan.has_point_times && pose.dur > 0;
}

OdometryPoses::OdometryPoses(const odometry::Params& params, std::unique_ptr<CanPriorStream> can)
    : odo_(params), can_(std::move(can)) {}

OdometryPoses::OdometryPoses(const odometry::Params& params) : OdometryPoses(params, nullptr) {}

OdometryPoses::~OdometryPoses() = default;

std::string OdometryPoses::describe() const { return can_ ? "odometry+can" : "odometry"; }

SweepPose OdometryPoses::pose(Scan& scan) {
  SweepPose sp;
  sp.stamp_s = scan.stamp_s;
  sp.dur = sweepDuration(scan);
  std::optional<odometry::MotionPrior> prior;
  if (can_ && prev_) {
    const double t_prev = prev_->stamp_s, t_curr = odo_.poseTimeOf(scan);
    prior = can_->between(t_prev, t_curr);
    sp.T_baseprev_basecurr = can_->baseMotion(t_prev, t_curr);
    sp.T_base_lidar = can_->baseToLidar();
  }
  const odometry::FrameResult res = keep_scans_ ? odo_.process(scan, prior) : odo_.process(std::move(scan), prior);
  // The wheel odometry learns its yaw-rate bias and speed scale from the LiDAR between two converged
  // frames (a Degenerate frame's motion came partly from the wheels themselves).
  if (can_ && prev_ && (converged(prev_->status) || prev_->status == odometry::FrameStatus::First) &&
      converged(res.status)) {
    can_->observeLidarMotion(prev_->stamp_s, res.stamp_s, prev_->T_world_lidar.inverse() * res.T_world_lidar);
  }
  prev_ = res;
  sp.odometry = res;
  sp.points_lidar = &odo_.lastFramePoints();
  if (res.status == odometry::FrameStatus::Skipped) {
    sp.why = "odometry skipped the sweep";
    return sp;
  }
  // The odometry's pose is mid-sweep; the sweep's ends assume the motion since the last pose went on.
  sp.ok = true, sp.ref = res.T_world_lidar, sp.t_ref = res.stamp_s;
  const Eigen::Isometry3d half = interpolate(Eigen::Isometry3d::Identity(), T_prev_.inverse() * sp.ref, 0.5);
  sp.deskew = have_prev_ && sp.dur > 0;
  sp.start = sp.ref * half.inverse(), sp.end = sp.ref * half;
  T_prev_ = sp.ref, have_prev_ = true;
  return sp;
}

TrajectoryPoses::TrajectoryPoses(const std::string& tum_path) : path_(tum_path) {
  auto traj = datasets::readTum(tum_path);
  stamps_s_ = std::move(traj.stamps_s);
  poses_ = std::move(traj.poses);
}

SweepPose TrajectoryPoses::pose(Scan& scan) {
  SweepPose sp;
  sp.stamp_s = scan.stamp_s;
  sp.dur = sweepDuration(scan);
  sp.t_ref = scan.stamp_s + 0.5 * sp.dur;
  const auto a = interpolatePose(stamps_s_, poses_, scan.stamp_s);
  const auto b = interpolatePose(stamps_s_, poses_, scan.stamp_s + sp.dur);
  const auto r = interpolatePose(stamps_s_, poses_, sp.t_ref);
  if (!a || !b || !r) {
    sp.why = "no pose in the trajectory at this sweep";
    return sp;
  }
  sp.ok = sp.deskew = true, sp.start = *a, sp.end = *b, sp.ref = *r;
  return sp;
}

RecordedPoses::RecordedPoses(std::vector<SweepPose> poses, std::string input, std::string origin)
    : poses_(std::move(poses)), input_(std::move(input)), origin_(std::move(origin)) {}

SweepPose RecordedPoses::pose(Scan& scan) {
  if (next_ >= poses_.size()) {
    throw std::runtime_error("'" + input_ + "' gave more sweeps on its second reading than on its first");
  }
  if (poses_[next_].stamp_s != scan.stamp_s) {
    throw std::runtime_error("'" + input_ + "' gave other sweeps on its second reading (sweep " +
                             std::to_string(next_) + ")");
  }
  return poses_[next_++];
}

}  // namespace roadslam::pipeline
