#include "roadslam/pipeline/can_prior.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>

#include "roadslam/can/candump.h"
#include "roadslam/pipeline/vehicle_prior.h"
#include "roadslam/vehicle/params.h"
#include "roadslam/vehicle/vehicle_state.h"

namespace roadslam::pipeline {

struct CanPriorStream::Impl {
  Impl(const std::string& log_path, const std::string& ini, const mrpt::config::CConfigFileBase& cfg)
      : path(log_path), log(log_path, vehicle::loadVehicleIni(ini)), prior(loadPriorParams(cfg), log.decoder().params()) {}

  static pipeline::VehiclePriorParams loadPriorParams(const mrpt::config::CConfigFileBase& cfg) {
    pipeline::VehiclePriorParams p;
    p.loadFromConfigFile(cfg, "vehicle_prior");
    return p;
  }

  /// Feeds every frame stamped up to \p t_s [s].
  void advanceTo(double t_s) {
    frames += log.readUntil(t_s, [this](const vehicle::VehicleState& s, vehicle::UpdateMask m) { prior.update(s, m); });
  }

  std::string path;
  vehicle::VehicleLogReader log;
  pipeline::VehiclePrior prior;
  size_t frames = 0;
};

CanPriorStream::CanPriorStream(const std::string& can_log, const std::string& vehicle_ini,
                               const mrpt::config::CConfigFileBase& cfg)
    : impl_(std::make_unique<Impl>(can_log, vehicle_ini, cfg)) {}

CanPriorStream::~CanPriorStream() = default;

std::optional<odometry::MotionPrior> CanPriorStream::between(double t_prev_s, double t_curr_s) {
  impl_->advanceTo(t_curr_s);
  auto p = impl_->prior.between(t_prev_s, t_curr_s);
  ++(p ? given_ : missing_);
  return p;
}

std::optional<Eigen::Isometry3d> CanPriorStream::baseMotion(double t_prev_s, double t_curr_s) {
  impl_->advanceTo(t_curr_s);
  return impl_->prior.baseMotion(t_prev_s, t_curr_s);
}

const Eigen::Isometry3d& CanPriorStream::baseToLidar() const { return impl_->prior.params().T_base_lidar; }

bool CanPriorStream::observeLidarMotion(double t_prev_s, double t_curr_s, const Eigen::Isometry3d& T_lidarprev_lidarcurr) {
  impl_->advanceTo(t_curr_s);
  return impl_->prior.observeLidarMotion(t_prev_s, t_curr_s, T_lidarprev_lidarcurr) != vehicle::CalibrationUse::Rejected;
}

nlohmann::json CanPriorStream::calibrationJson() const {
  constexpr double kDeg = M_PI / 180;
  const auto& dr = impl_->prior.deadReckoning();
  const auto& cal = impl_->prior.calibrator();
  const auto bias = cal.yawRateBias();
  const auto scale = cal.speedScale();
  const auto& st = cal.stats();
  return {{"online", impl_->prior.params().calibration.enabled},
          {"yaw_rate_bias_deg_s", dr.yawRateBias() / kDeg},
          {"speed_scale", dr.speedScale()},
          {"standstill_bias_samples", dr.stats().bias_samples},
          {"online_yaw_rate_bias_deg_s", bias ? nlohmann::json(*bias / kDeg) : nlohmann::json()},
          {"online_speed_scale", scale ? nlohmann::json(*scale) : nlohmann::json()},
          {"intervals", st.intervals}, {"bias_intervals", st.bias_used}, {"scale_intervals", st.scale_used},
          {"rejected_intervals", st.rejected}, {"bias_window_s", st.bias_time_s},
          {"scale_window_m", st.scale_distance_m}};
}

size_t CanPriorStream::framesRead() const { return impl_->frames; }
std::string CanPriorStream::describe() const { return "candump:" + impl_->path; }

}  // namespace roadslam::pipeline
