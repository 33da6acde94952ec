#include "roadslam/pipeline/vehicle_prior.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cmath>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::pipeline {
namespace {
double wrapPi(double a) { return std::atan2(std::sin(a), std::cos(a)); }

Eigen::Isometry3d planar(double x, double y, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0);
  return T;
}
}  // namespace

// The mounting pose T_base_lidar as six keys: lidar_x_m, lidar_y_m, lidar_z_m [m] and the ZYX Euler
// angles lidar_yaw_deg, lidar_pitch_deg, lidar_roll_deg [deg].
void VehiclePriorParams::fields(ParamTable& t) {
  Eigen::Vector3d xyz = T_base_lidar.translation();
  Eigen::Vector3d ypr = T_base_lidar.linear().eulerAngles(2, 1, 0);
  t.num("lidar_x_m", xyz.x());
  t.num("lidar_y_m", xyz.y());
  t.num("lidar_z_m", xyz.z());
  t.angle("lidar_yaw_deg", ypr(0));
  t.angle("lidar_pitch_deg", ypr(1));
  t.angle("lidar_roll_deg", ypr(2));
  if (t.loading()) {
    T_base_lidar = Eigen::Isometry3d::Identity();
    T_base_lidar.linear() = (Eigen::AngleAxisd(ypr(0), Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(ypr(1), Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(ypr(2), Eigen::Vector3d::UnitX())).toRotationMatrix();
    T_base_lidar.translation() = xyz;
  }
  t.num("max_extrapolation_s", max_extrapolation_s);
  t.num("history_s", history_s);
}

void VehiclePriorParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  if (max_extrapolation_s < 0) throw std::runtime_error("[" + s + "] max_extrapolation_s must be >= 0");
  if (history_s <= 0) throw std::runtime_error("[" + s + "] history_s must be > 0");
  dead_reckoning.loadFromConfigFile(cfg, s);
  calibration.loadFromConfigFile(cfg, s);
}

void VehiclePriorParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
  dead_reckoning.saveToConfigFile(cfg, s);
  calibration.saveToConfigFile(cfg, s);
}

VehiclePrior::VehiclePrior(const VehiclePriorParams& params, const vehicle::VehicleParams& vehicle)
    : p_(params), dr_(params.dead_reckoning, vehicle), cal_(params.calibration) {}

void VehiclePrior::update(const vehicle::VehicleState& state, vehicle::UpdateMask mask) {
  if (!dr_.update(state, mask)) return;
  poses_.push_back(dr_.pose());
  while (!poses_.empty() && poses_.front().t_s < poses_.back().t_s - p_.history_s) poses_.pop_front();
}

std::optional<vehicle::Pose2D> VehiclePrior::poseAt(double t) const {
  if (poses_.empty() || t < poses_.front().t_s) return std::nullopt;
  const vehicle::Pose2D& last = poses_.back();
  if (t >= last.t_s) {  // constant velocity past the newest pose (arc of the last v, w)
    const double dt = t - last.t_s;
    if (dt > p_.max_extrapolation_s) return std::nullopt;
    vehicle::Pose2D p = last;
    const double yaw_mid = last.yaw_rad + 0.5 * last.w_radps * dt;
    p.x_m += last.v_mps * dt * std::cos(yaw_mid);
    p.y_m += last.v_mps * dt * std::sin(yaw_mid);
    p.yaw_rad += last.w_radps * dt;
    p.raw_distance_m += std::abs(last.v_mps) / dr_.speedScale() * dt;
    p.raw_yaw_rad += (last.w_radps + dr_.yawRateBias()) * dt;
    p.t_s = t;
    return p;
  }
  const auto it = std::upper_bound(poses_.begin(), poses_.end(), t,
                                   [](double x, const vehicle::Pose2D& q) { return x < q.t_s; });
  const vehicle::Pose2D& b = *it;
  const vehicle::Pose2D& a = *(it - 1);
  const double u = b.t_s > a.t_s ? (t - a.t_s) / (b.t_s - a.t_s) : 0.0;
  vehicle::Pose2D p = a;
  p.t_s = t;
  p.x_m += u * (b.x_m - a.x_m);
  p.y_m += u * (b.y_m - a.y_m);
  p.yaw_rad += u * wrapPi(b.yaw_rad - a.yaw_rad);
  p.v_mps += u * (b.v_mps - a.v_mps);
  p.raw_yaw_rad += u * (b.raw_yaw_rad - a.raw_yaw_rad);
  p.raw_distance_m += u * (b.raw_distance_m - a.raw_distance_m);
  return p;
}

std::optional<Eigen::Isometry3d> VehiclePrior::baseMotion(double t_prev_s, double t_curr_s) const {
  const auto a = poseAt(t_prev_s), b = poseAt(t_curr_s);
  if (!a || !b) return std::nullopt;
  return planar(a->x_m, a->y_m, a->yaw_rad).inverse() * planar(b->x_m, b->y_m, b->yaw_rad);
}

std::optional<odometry::MotionPrior> VehiclePrior::between(double t_prev_s, double t_curr_s) const {
  const auto T_baseprev_basecurr = baseMotion(t_prev_s, t_curr_s);
  if (!T_baseprev_basecurr) return std::nullopt;
  odometry::MotionPrior m;
  m.T_prev_curr = p_.T_base_lidar.inverse() * *T_baseprev_basecurr * p_.T_base_lidar;
  m.speed_mps = poseAt(t_curr_s)->v_mps;
  return m;
}

vehicle::CalibrationUse VehiclePrior::observeLidarMotion(double t_prev_s, double t_curr_s,
                                                         const Eigen::Isometry3d& T_lidarprev_lidarcurr) {
  const auto a = poseAt(t_prev_s), b = poseAt(t_curr_s);
  if (!p_.calibration.enabled || !a || !b) return vehicle::CalibrationUse::Rejected;
  // The lidar's motion seen from the base: T_baseprev_basecurr = T_base_lidar * T_lp_lc * T_base_lidar^-1.
  const Eigen::Isometry3d T_b = p_.T_base_lidar * T_lidarprev_lidarcurr * p_.T_base_lidar.inverse();
  vehicle::CalibrationInterval in;
  in.dt_s = t_curr_s - t_prev_s;
  in.ref_yaw_rad = std::atan2(T_b.linear()(1, 0), T_b.linear()(0, 0));
  in.ref_distance_m = T_b.translation().norm();
  in.raw_yaw_rad = b->raw_yaw_rad - a->raw_yaw_rad;
  in.raw_distance_m = b->raw_distance_m - a->raw_distance_m;
  const auto use = cal_.add(in);
  if (const auto bias = cal_.yawRateBias()) dr_.setYawRateBias(*bias);
  if (const auto scale = cal_.speedScale()) dr_.setSpeedScale(*scale);
  return use;
}

}  // namespace roadslam::pipeline
