#include "roadslam/sim/lidar.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"

namespace roadslam::sim {

namespace {
constexpr double kDeg = M_PI / 180.0;
using velodyne::kVlp16LaserPeriod_s;
using velodyne::kVlp16Lasers;
using velodyne::kVlp16SequencePeriod_s;
using velodyne::kVlp16SequencesPerPacket;
}  // namespace

#define RS_LIDAR_KEYS(X)                                                                         \
  X(rotation_hz) X(start_azimuth_deg) X(max_range_m) X(min_range_m) X(range_noise_m)             \
  X(dropout_prob) X(min_signal) X(max_incidence_deg) X(mount_x_m) X(mount_y_m) X(mount_height_m) \
  X(mount_roll_deg) X(mount_pitch_deg) X(mount_yaw_deg) X(jitter_deg)

void LidarParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s) {
#define RS_LOAD(k) k = readDouble(c, s, #k, k);
  RS_LIDAR_KEYS(RS_LOAD)
#undef RS_LOAD
  if (rotation_hz < 5 || rotation_hz > 20)
    throw std::runtime_error("[" + s + "] rotation_hz must be within 5..20 (VLP-16: 300-1200 rpm)");
  if (max_range_m <= 0 || max_range_m > 130 || min_range_m < 0 || range_noise_m < 0 ||
      dropout_prob < 0 || dropout_prob > 1)
    throw std::runtime_error("[" + s + "] max_range_m must be in (0, 130], min_range_m, "
                             "range_noise_m >= 0, dropout_prob in [0, 1]");
}

void LidarParams::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const {
#define RS_SAVE(k) c.write(s, #k, k);
  RS_LIDAR_KEYS(RS_SAVE)
#undef RS_SAVE
}

std::vector<std::string> LidarParams::keys() {
#define RS_NAME(k) #k,
  return {RS_LIDAR_KEYS(RS_NAME)};
#undef RS_NAME
}

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

LidarSimulator::LidarSimulator(const World& world, const Trajectory& trajectory,
                               const LidarParams& params, uint64_t seed)
    : world_(world), traj_(trajectory), p_(params), seed_(mix64(seed ^ 0x11DA4ull)) {
  T_vehicle_lidar_ = Pose3::fromXyzYpr(p_.mount_x_m, p_.mount_y_m, p_.mount_height_m,
                                       p_.mount_yaw_deg * kDeg, p_.mount_pitch_deg * kDeg,
                                       p_.mount_roll_deg * kDeg);
  for (int i = 0; i < kVlp16Lasers; ++i) {
    const double e = elevationDeg(i) * kDeg;
    dir_el_[static_cast<std::size_t>(i)] = {std::cos(e), std::sin(e), e};
  }
  for (int i = 0; i < 3; ++i) jitter_phase_[i] = 2 * M_PI * uniform01(seed_ + 101 + i);
  cars_.resize(world.cars.size());
}

double LidarSimulator::packetPeriod_s() { return kVlp16SequencesPerPacket * kVlp16SequencePeriod_s; }

double LidarSimulator::elevationDeg(int laser) { return (laser % 2 == 0) ? -15 + laser : laser; }

Pose3 LidarSimulator::lidarPose(double t_s) const {
  const VehicleState s = traj_.at(t_s);
  return Pose3::fromXyzYpr(s.x, s.y, s.z, s.yaw, s.pitch, s.roll).compose(T_vehicle_lidar_);
}

void LidarSimulator::simulatePacket(
    uint64_t k, std::array<velodyne::FiringSequence, kVlp16SequencesPerPacket>& seq,
    std::vector<TrueReturn>* truth) {
  const double t0 = static_cast<double>(k) * packetPeriod_s();
  // Moving cars advance < 3 cm within a packet at 72 km/h: one pose per packet.
  for (std::size_t c = 0; c < cars_.size(); ++c)
    cars_[c] = world_.carPrism(world_.cars[c], t0 + 0.5 * packetPeriod_s());
  const double deg_per_s = 360.0 * p_.rotation_hz, J = p_.jitter_deg * kDeg;
  const double cos_max_inc = std::cos(p_.max_incidence_deg * kDeg);
  for (int q = 0; q < kVlp16SequencesPerPacket; ++q) {
    const double tq = t0 + q * kVlp16SequencePeriod_s;
    // One sensor pose per 55 us sequence: at 25 m/s the 16 firings span < 0.9 mm of travel,
    // below the 2 mm range quantisation.
    const Pose3 jitter = Pose3::fromXyzYpr(
        0, 0, 0, 0.5 * J * std::sin(2 * M_PI * 5.3 * tq + jitter_phase_[2]),
        J * std::sin(2 * M_PI * 7.9 * tq + jitter_phase_[1]), J * std::sin(2 * M_PI * 11.3 * tq + jitter_phase_[0]));
    const Pose3 T_world_lidar = lidarPose(tq).compose(jitter);
    auto& fs = seq[static_cast<std::size_t>(q)];
    fs.azimuth_deg = std::fmod(p_.start_azimuth_deg + deg_per_s * tq, 360.0);
    for (int i = 0; i < kVlp16Lasers; ++i) {
      const double ti = tq + i * kVlp16LaserPeriod_s;
      const double az = std::fmod(p_.start_azimuth_deg + deg_per_s * ti, 360.0);
      const Vec3& ce = dir_el_[static_cast<std::size_t>(i)];
      const double a = az * kDeg;
      const Ray ray{T_world_lidar.t, T_world_lidar.rotate({ce.x * std::cos(a), -ce.x * std::sin(a), ce.y})};
      const uint64_t key = mix64(seed_ ^ (k * 384 + static_cast<uint64_t>(q) * 16 + static_cast<uint64_t>(i)));
      velodyne::LaserReturn& out = fs.strongest[static_cast<std::size_t>(i)];
      out = {};
      ++counters_.rays;
      Hit hit;
      if (!world_.raycast(ray, p_.max_range_m, key, cars_.data(), cars_.size(), hit)) {
        ++counters_.no_hit;
        continue;
      }
      const double cos_inc = std::abs(hit.n.x * ray.d.x + hit.n.y * ray.d.y + hit.n.z * ray.d.z);
      const MaterialProps& m = materialProps(hit.material);
      const double signal = m.reflectivity * cos_inc * 100.0 / std::max(100.0, hit.t * hit.t);
      if (hit.t < p_.min_range_m) { ++counters_.too_close; continue; }
      if (cos_inc < cos_max_inc) { ++counters_.grazing; continue; }
      if (signal < p_.min_signal) { ++counters_.dark; continue; }
      if (uniform01(key + 1) < p_.dropout_prob + m.dropout) { ++counters_.dropped; continue; }
      const double u1 = 1.0 - uniform01(key + 2), u2 = uniform01(key + 3);
      const double noise = p_.range_noise_m * std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
      out.range_m = static_cast<float>(std::max(0.01, hit.t + noise));
      // Calibrated reflectivity: 0-100 diffuse, 101-255 retro-reflectors (VLP-16 manual 7.2).
      out.intensity = static_cast<uint8_t>(std::clamp(100.0 * m.reflectivity * (0.3 + 0.7 * cos_inc), 0.0, 255.0));
      ++counters_.returns;
      if (truth)
        truth->push_back({ti, k, static_cast<uint8_t>(q), static_cast<uint8_t>(i),
                          static_cast<uint8_t>((elevationDeg(i) + 15) / 2), out.intensity, az,
                          out.range_m, {ray.o.x + hit.t * ray.d.x, ray.o.y + hit.t * ray.d.y, ray.o.z + hit.t * ray.d.z}});
    }
  }
}

}  // namespace roadslam::sim
