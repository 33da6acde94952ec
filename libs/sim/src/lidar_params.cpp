// LidarParams (section [lidar]) and the rigid transforms of the sensor model.
#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "roadslam/sim/lidar.h"

namespace roadslam::sim {

#define RS_LIDAR_KEYS(X)                                                                         \
  X(rotation_hz) X(start_azimuth_deg) X(max_range_m) X(min_range_m) X(range_noise_m)             \
  X(dropout_prob) X(min_signal) X(max_incidence_deg) X(mount_x_m) X(mount_y_m) X(mount_height_m) \
  X(mount_roll_deg) X(mount_pitch_deg) X(mount_yaw_deg) X(jitter_deg) X(azimuth_resolution_deg)  \
  X(beam_divergence_mrad) X(mixed_pixel_prob) X(mixed_pixel_min_gap_m) X(calib_elevation_std_deg) \
  X(calib_azimuth_std_deg) X(calib_range_std_m) X(calib_elevation_bias_deg)

void LidarParams::fields(ParamTable& t) {
#define RS_FIELD(k) t.num(#k, k);
  RS_LIDAR_KEYS(RS_FIELD)
#undef RS_FIELD
  t.text("model", model);
  t.num("footprint_rays", footprint_rays);
}

void LidarParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s) {
  loadFields(*this, c, s);
  if (model != "vlp16" && model != "hdl64")
    throw std::runtime_error("[" + s + "] model: '" + model + "' is not vlp16|hdl64");
  if (azimuth_resolution_deg < 0.05 || azimuth_resolution_deg > 0.5)
    throw std::runtime_error("[" + s + "] azimuth_resolution_deg must be within 0.05..0.5");
  if (beam_divergence_mrad < 0 || beam_divergence_mrad > 20 || footprint_rays < 1 || footprint_rays > 16)
    throw std::runtime_error("[" + s + "] beam_divergence_mrad must be within 0..20, footprint_rays 1..16");
  if (mixed_pixel_prob < 0 || mixed_pixel_prob > 1 || mixed_pixel_min_gap_m <= 0)
    throw std::runtime_error("[" + s + "] mixed_pixel_prob must be in [0, 1], mixed_pixel_min_gap_m > 0");
  if (mixed_pixel_prob > 0 && beam_divergence_mrad <= 0)
    throw std::runtime_error("[" + s + "] mixed_pixel_prob > 0 needs beam_divergence_mrad > 0 (a footprint)");
  if (calib_elevation_std_deg < 0 || calib_azimuth_std_deg < 0 || calib_range_std_m < 0 ||
      std::abs(calib_elevation_bias_deg) > 2)
    throw std::runtime_error("[" + s + "] calib_*_std must be >= 0, |calib_elevation_bias_deg| <= 2");
  if (rotation_hz < 5 || rotation_hz > 20)
    throw std::runtime_error("[" + s + "] rotation_hz must be within 5..20 (VLP-16: 300-1200 rpm)");
  if (max_range_m <= 0 || max_range_m > 130 || min_range_m < 0 || range_noise_m < 0 ||
      dropout_prob < 0 || dropout_prob > 1)
    throw std::runtime_error("[" + s + "] max_range_m must be in (0, 130], min_range_m, "
                             "range_noise_m >= 0, dropout_prob in [0, 1]");
}

void LidarParams::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const {
  saveFields(*this, c, s);
}

std::vector<std::string> LidarParams::keys() { return fieldKeys<LidarParams>(); }

Vec3 Pose3::rotate(const Vec3& v) const {
  return {R[0] * v.x + R[1] * v.y + R[2] * v.z, R[3] * v.x + R[4] * v.y + R[5] * v.z,
          R[6] * v.x + R[7] * v.y + R[8] * v.z};
}
Vec3 Pose3::apply(const Vec3& p) const {
  const Vec3 r = rotate(p);
  return {r.x + t.x, r.y + t.y, r.z + t.z};
}
Pose3 Pose3::compose(const Pose3& b) const {
  Pose3 o;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      o.R[3 * i + j] = R[3 * i] * b.R[j] + R[3 * i + 1] * b.R[3 + j] + R[3 * i + 2] * b.R[6 + j];
  o.t = apply(b.t);
  return o;
}
Pose3 Pose3::fromXyzYpr(double x, double y, double z, double yaw, double pitch, double roll) {
  // R = Rz(yaw) Ry(pitch) Rx(roll)
  const double cy = std::cos(yaw), sy = std::sin(yaw), cp = std::cos(pitch), sp = std::sin(pitch);
  const double cr = std::cos(roll), sr = std::sin(roll);
  Pose3 o;
  o.R = {cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,
         sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,
         -sp,     cp * sr,                cp * cr};
  o.t = {x, y, z};
  return o;
}
std::array<double, 4> Pose3::quaternion() const {
  // Shepperd's method: pivot on the largest diagonal term for accuracy.
  const double tr = R[0] + R[4] + R[8];
  double qx, qy, qz, qw;
  if (tr > 0) {
    const double s = 2 * std::sqrt(tr + 1);
    qw = 0.25 * s; qx = (R[7] - R[5]) / s; qy = (R[2] - R[6]) / s; qz = (R[3] - R[1]) / s;
  } else if (R[0] > R[4] && R[0] > R[8]) {
    const double s = 2 * std::sqrt(1 + R[0] - R[4] - R[8]);
    qw = (R[7] - R[5]) / s; qx = 0.25 * s; qy = (R[1] + R[3]) / s; qz = (R[2] + R[6]) / s;
  } else if (R[4] > R[8]) {
    const double s = 2 * std::sqrt(1 + R[4] - R[0] - R[8]);
    qw = (R[2] - R[6]) / s; qx = (R[1] + R[3]) / s; qy = 0.25 * s; qz = (R[5] + R[7]) / s;
  } else {
    const double s = 2 * std::sqrt(1 + R[8] - R[0] - R[4]);
    qw = (R[3] - R[1]) / s; qx = (R[2] + R[6]) / s; qy = (R[5] + R[7]) / s; qz = 0.25 * s;
  }
  if (qw < 0) { qx = -qx; qy = -qy; qz = -qz; qw = -qw; }
  return {qx, qy, qz, qw};
}

}  // namespace roadslam::sim
