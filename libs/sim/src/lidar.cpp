#include "roadslam/sim/lidar.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::sim {

namespace {
using unit::kDeg;
using velodyne::kVlp16LaserPeriod_s;
using velodyne::kVlp16Lasers;
using velodyne::kVlp16SequencePeriod_s;
using velodyne::kVlp16SequencesPerPacket;
}  // namespace

LidarSimulator::LidarSimulator(const World& world, const Trajectory& trajectory,
                               const LidarParams& params, uint64_t seed)
    : world_(world), traj_(trajectory), p_(params), seed_(mix64(seed ^ 0x11DA4ull)) {
  T_vehicle_lidar_ = Pose3::fromXyzYpr(p_.mount_x_m, p_.mount_y_m, p_.mount_height_m,
                                       p_.mount_yaw_deg * kDeg, p_.mount_pitch_deg * kDeg,
                                       p_.mount_roll_deg * kDeg);
  // Calibration error drawn once per laser from its own stream (the noise keys are untouched).
  Rng cal{mix64(seed_ ^ 0xCA11B2A7ull)};
  const int n = p_.lasers();
  calib_.resize(static_cast<std::size_t>(n));
  dir_el_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    LaserCalibration& c = calib_[static_cast<std::size_t>(i)];
    if (p_.calib_elevation_std_deg > 0) c.elevation_rad = p_.calib_elevation_std_deg * kDeg * cal.normal();
    if (p_.calib_elevation_bias_deg != 0) c.elevation_rad += p_.calib_elevation_bias_deg * kDeg;
    if (p_.calib_azimuth_std_deg > 0) c.azimuth_rad = p_.calib_azimuth_std_deg * kDeg * cal.normal();
    if (p_.calib_range_std_m > 0) c.range_m = p_.calib_range_std_m * cal.normal();
    const double e = nominalElevationDeg(i) * kDeg + c.elevation_rad;
    dir_el_[static_cast<std::size_t>(i)] = {std::cos(e), std::sin(e), e};
  }
  columns_ = 2 * static_cast<int>(std::lround(180.0 / p_.azimuth_resolution_deg));
  cos_max_inc_ = std::cos(p_.max_incidence_deg * kDeg);
  for (int i = 0; i < 3; ++i) jitter_phase_[i] = 2 * M_PI * uniform01(seed_ + 101 + i);
  cars_.resize(world.cars.size());
  car_returns_.resize(world.cars.size());
}

double LidarSimulator::packetPeriod_s() { return kVlp16SequencesPerPacket * kVlp16SequencePeriod_s; }

double LidarSimulator::elevationDeg(int laser) { return (laser % 2 == 0) ? -15 + laser : laser; }

double LidarSimulator::elevationDegHdl64(int laser) {
  return laser < 32 ? 2.0 - laser / 3.0 : -8.83 - (laser - 32) * (24.8 - 8.83) / 31.0;
}

double LidarSimulator::nominalElevationDeg(int laser) const {
  return p_.hdl64() ? elevationDegHdl64(laser) : elevationDeg(laser);
}

int LidarSimulator::ring(int laser) const {
  return p_.hdl64() ? 63 - laser : static_cast<int>((elevationDeg(laser) + 15) / 2);
}

Pose3 LidarSimulator::lidarPose(double t_s) const {
  const VehicleState s = traj_.at(t_s);
  return Pose3::fromXyzYpr(s.x, s.y, s.z, s.yaw, s.pitch, s.roll).compose(T_vehicle_lidar_);
}

void LidarSimulator::updateCars(double t_s) {
  for (std::size_t c = 0; c < cars_.size(); ++c) cars_[c] = world_.carPrism(world_.cars[c], t_s);
}

namespace {
Pose3 jitterPose(double J, double t, const double* phase) {
  return Pose3::fromXyzYpr(0, 0, 0, 0.5 * J * std::sin(2 * M_PI * 5.3 * t + phase[2]),
                           J * std::sin(2 * M_PI * 7.9 * t + phase[1]),
                           J * std::sin(2 * M_PI * 11.3 * t + phase[0]));
}
}  // namespace

bool LidarSimulator::footprintRange(const Ray& centre, const Vec3& u, const Vec3& v, uint64_t key,
                                    double& range, Hit& rep) {
  // The footprint: its centre and footprint_rays rays on the rim of the divergence cone (half
  // angle = divergence / 2), each cast exactly (foliage decides per sub-ray).
  const int n = p_.footprint_rays + 1;
  const double th = 0.5e-3 * p_.beam_divergence_mrad;
  double t[17];
  Hit hits[17];
  int n_hit = 0;
  double t_near = 1e300, t_far = -1;
  for (int j = 0; j < n; ++j) {
    Ray r = centre;
    uint64_t k = key;
    if (j > 0) {
      const double phi = 2 * M_PI * (j - 1) / p_.footprint_rays, cu = th * std::cos(phi), cv = th * std::sin(phi);
      Vec3 d{centre.d.x + cu * u.x + cv * v.x, centre.d.y + cu * u.y + cv * v.y, centre.d.z + cu * u.z + cv * v.z};
      const double inv = 1.0 / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
      r.d = {d.x * inv, d.y * inv, d.z * inv};
      k = mix64(key + 16 + static_cast<uint64_t>(j));
    }
    Hit h;
    if (!world_.raycast(r, p_.max_range_m, k, cars_.data(), cars_.size(), h)) continue;
    t[n_hit] = h.t;
    hits[n_hit++] = h;
    t_near = std::min(t_near, h.t);
    t_far = std::max(t_far, h.t);
  }
  if (n_hit == 0) return false;
  // One surface: the pulse's energy-weighted mean over the footprint (a slanted surface widens the
  // echo; its centroid is the mean range of the footprint).
  double near_sum = 0, far_sum = 0;
  int n_near = 0;
  int near_rep = -1, far_rep = -1;
  for (int j = 0; j < n_hit; ++j) {
    if (t[j] < t_near + p_.mixed_pixel_min_gap_m) {
      near_sum += t[j];
      ++n_near;
      if (near_rep < 0) near_rep = j;
    } else {
      far_sum += t[j];
      if (far_rep < 0) far_rep = j;
    }
  }
  const int n_far = n_hit - n_near;
  if (n_far == 0) {
    range = near_sum / n_near;
    rep = hits[near_rep];
    return true;
  }
  // A depth edge inside the footprint: two echoes. With mixed_pixel_prob the receiver merges them
  // into one range between the surfaces, weighted by the energy on each (Hebert & Krotkov 1992,
  // "3D measurements from imaging laser radars: how good are they?"); else the stronger echo.
  const double t_n = near_sum / n_near, t_f = far_sum / n_far, w = static_cast<double>(n_near) / n_hit;
  if (uniform01(key + 4) < p_.mixed_pixel_prob) {
    range = w * t_n + (1 - w) * t_f;
    rep = hits[near_rep];
  } else if (n_near >= n_far) {
    range = t_n;
    rep = hits[near_rep];
  } else {
    range = t_f;
    rep = hits[far_rep];
  }
  return true;
}

bool LidarSimulator::fire(const Pose3& T_world_lidar, int i, double az_deg, uint64_t key, Echo& echo) {
  const Vec3& ce = dir_el_[static_cast<std::size_t>(i)];
  const LaserCalibration& cal = calib_[static_cast<std::size_t>(i)];
  // The ray goes along the true (miscalibrated) angles; the output reports the nominal ones.
  const double a = az_deg * kDeg + cal.azimuth_rad;
  const double ca = std::cos(a), sa = std::sin(a);
  const Ray ray{T_world_lidar.t, T_world_lidar.rotate({ce.x * ca, -ce.x * sa, ce.y})};
  ++counters_.rays;
  Hit hit;
  if (p_.beam_divergence_mrad > 0) {
    // Footprint axes: along the azimuth and the elevation (lidar frame), rotated to the world.
    const Vec3 u = T_world_lidar.rotate({-sa, -ca, 0}), v = T_world_lidar.rotate({-ce.y * ca, ce.y * sa, ce.x});
    double range = 0;
    if (!footprintRange(ray, u, v, key, range, hit)) {
      ++counters_.no_hit;
      return false;
    }
    hit.t = range;
  } else if (!world_.raycast(ray, p_.max_range_m, key, cars_.data(), cars_.size(), hit)) {
    ++counters_.no_hit;
    return false;
  }
  const double cos_inc = std::abs(hit.n.x * ray.d.x + hit.n.y * ray.d.y + hit.n.z * ray.d.z);
  const MaterialProps& m = materialProps(hit.material);
  const double signal = m.reflectivity * cos_inc * 100.0 / std::max(100.0, hit.t * hit.t);
  if (hit.t < p_.min_range_m) { ++counters_.too_close; return false; }
  if (cos_inc < cos_max_inc_) { ++counters_.grazing; return false; }
  if (signal < p_.min_signal) { ++counters_.dark; return false; }
  if (uniform01(key + 1) < p_.dropout_prob + m.dropout) { ++counters_.dropped; return false; }
  const double u1 = 1.0 - uniform01(key + 2), u2 = uniform01(key + 3);
  const double noise = p_.range_noise_m * std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
  echo.range_m = std::max(0.01, hit.t + cal.range_m + noise);
  echo.intensity = 100.0 * m.reflectivity * (0.3 + 0.7 * cos_inc);
  echo.p_world = {ray.o.x + hit.t * ray.d.x, ray.o.y + hit.t * ray.d.y, ray.o.z + hit.t * ray.d.z};
  echo.car = hit.dynamic;
  ++counters_.returns;
  return true;
}

void LidarSimulator::countCarReturn(const Echo& e, double t_s) {
  if (e.car < 0) return;
  auto& per_sample = car_returns_[static_cast<std::size_t>(e.car)];
  const auto k = static_cast<std::size_t>(std::max(0LL, std::llround(t_s / kCarSample_s)));
  if (per_sample.size() <= k) per_sample.resize(k + 1, 0);
  ++per_sample[k];
}

void LidarSimulator::simulatePacket(
    uint64_t k, std::array<velodyne::FiringSequence, kVlp16SequencesPerPacket>& seq,
    std::vector<TrueReturn>* truth) {
  if (p_.hdl64()) throw std::logic_error("simulatePacket: the lidar model is hdl64 (no VLP-16 packets)");
  const double t0 = static_cast<double>(k) * packetPeriod_s();
  // Moving cars advance < 3 cm within a packet at 72 km/h: one pose per packet.
  updateCars(t0 + 0.5 * packetPeriod_s());
  const double deg_per_s = 360.0 * p_.rotation_hz, J = p_.jitter_deg * kDeg;
  for (int q = 0; q < kVlp16SequencesPerPacket; ++q) {
    const double tq = t0 + q * kVlp16SequencePeriod_s;
    // One sensor pose per 55 us sequence: at 25 m/s the 16 firings span < 0.9 mm of travel,
    // below the 2 mm range quantisation.
    const Pose3 T_world_lidar = lidarPose(tq).compose(jitterPose(J, tq, jitter_phase_));
    auto& fs = seq[static_cast<std::size_t>(q)];
    fs.azimuth_deg = std::fmod(p_.start_azimuth_deg + deg_per_s * tq, 360.0);
    for (int i = 0; i < kVlp16Lasers; ++i) {
      const double ti = tq + i * kVlp16LaserPeriod_s;
      const double az = std::fmod(p_.start_azimuth_deg + deg_per_s * ti, 360.0);
      const uint64_t key = mix64(seed_ ^ (k * 384 + static_cast<uint64_t>(q) * 16 + static_cast<uint64_t>(i)));
      velodyne::LaserReturn& out = fs.strongest[static_cast<std::size_t>(i)];
      out = {};
      Echo e;
      if (!fire(T_world_lidar, i, az, key, e)) continue;
      countCarReturn(e, ti);
      out.range_m = static_cast<float>(e.range_m);
      // Calibrated reflectivity: 0-100 diffuse, 101-255 retro-reflectors (VLP-16 manual 7.2).
      out.intensity = static_cast<uint8_t>(std::clamp(e.intensity, 0.0, 255.0));
      if (truth)
        truth->push_back({ti, k, static_cast<uint8_t>(q), static_cast<uint8_t>(i),
                          static_cast<uint8_t>(ring(i)), out.intensity, az, out.range_m, e.p_world});
    }
  }
}

void LidarSimulator::simulateSweep(uint64_t k, Scan& scan, std::vector<TrueReturn>* truth) {
  if (!p_.hdl64()) throw std::logic_error("simulateSweep: the lidar model is vlp16 (packets)");
  // Column c fires at c / (N f), azimuth 180 + 360 j / N (clockwise from behind the car): the sweep
  // faces forward at its middle column, KITTI raw's stamp (Geiger et al., IJRR 2013, sec. 2).
  const int N = columns_;
  const double col_s = 1.0 / (N * p_.rotation_hz), J = p_.jitter_deg * kDeg, stamp = sweepStamp_s(k);
  scan = Scan{};
  scan.stamp_s = stamp;
  scan.has_point_times = scan.has_rings = true;
  scan.points.reserve(static_cast<std::size_t>(N) * 48);
  for (int j = 0; j < N; ++j) {
    const uint64_t c = k * static_cast<uint64_t>(N) + static_cast<uint64_t>(j);
    const double tc = static_cast<double>(c) * col_s;
    // Moving cars: one pose per 32 columns (< 1 ms: < 2 cm at 72 km/h).
    if (j % 32 == 0) updateCars(tc + 16 * col_s);
    // All 64 lasers of a column from one pose (the S2 fires them within ~50 us: < 1.3 mm at 25 m/s).
    const Pose3 T_world_lidar = lidarPose(tc).compose(jitterPose(J, tc, jitter_phase_));
    const double az = std::fmod(180.0 + 360.0 * j / N, 360.0), a = az * kDeg;
    for (int i = 0; i < 64; ++i) {
      Echo e;
      if (!fire(T_world_lidar, i, az, mix64(seed_ ^ 0x64BEA3ull ^ (c * 64 + static_cast<uint64_t>(i))), e)) continue;
      countCarReturn(e, tc);
      const double el = elevationDegHdl64(i) * kDeg, r = e.range_m;
      ScanPoint pt;
      pt.x = static_cast<float>(r * std::cos(el) * std::cos(a));
      pt.y = static_cast<float>(-r * std::cos(el) * std::sin(a));
      pt.z = static_cast<float>(r * std::sin(el));
      // KITTI reflectance [0..1]: 255 = the strongest retro-reflector.
      pt.intensity = static_cast<float>(std::clamp(e.intensity / 255.0, 0.0, 1.0));
      pt.t = static_cast<float>(tc - stamp);
      pt.ring = static_cast<uint16_t>(ring(i));
      scan.points.push_back(pt);
      if (truth)
        truth->push_back({tc, k, 0, static_cast<uint8_t>(i), static_cast<uint8_t>(ring(i)),
                          static_cast<uint8_t>(std::clamp(e.intensity, 0.0, 255.0)), az, r, e.p_world});
    }
  }
}

}  // namespace roadslam::sim
