#include "roadslam/sim/gnss_output.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/param_table.h"
#include "roadslam/gnss/geo.h"
#include "roadslam/gnss/nmea.h"
#include "roadslam/sim/simulator.h"

namespace roadslam::sim {

std::vector<std::string> GnssParams::keys() { return fieldKeys<GnssParams>(); }

void GnssParams::fields(ParamTable& t) {
  t.flag("enabled", enabled);
  t.num("rate_hz", rate_hz);
  t.num("origin_h_m", origin_h_m);
  t.num("lever_x_m", lever_x_m);
  t.num("lever_y_m", lever_y_m);
  t.num("lever_z_m", lever_z_m);
  t.num("noise_sigma_m", noise_sigma_m);
  t.num("noise_sigma_up_m", noise_sigma_up_m);
  t.num("bias_walk_m_per_sqrt_s", bias_walk_m_per_sqrt_s);
  t.num("latency_s", latency_s);
  t.num("hdop", hdop);
  t.num("satellites", satellites);
  t.flag("outage_in_tunnel", outage_in_tunnel);
  t.num("outage_start_s", outage_start_s);
  t.num("outage_duration_s", outage_duration_s);
  t.num("multipath_start_s", multipath_start_s);
  t.num("multipath_duration_s", multipath_duration_s);
  t.num("multipath_offset_m", multipath_offset_m);
  t.num("multipath_bearing_deg", multipath_bearing_deg);
}

void GnssParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  if (rate_hz < 0.1 || rate_hz > 20 || noise_sigma_m < 0 || noise_sigma_up_m < 0 || bias_walk_m_per_sqrt_s < 0 ||
      latency_s < 0 || hdop <= 0 || outage_duration_s < 0 || multipath_duration_s < 0) {
    throw std::runtime_error("[" + s + "] rate_hz must be in [0.1, 20], hdop > 0, the sigmas, latency and durations >= 0");
  }
}

void GnssParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

GnssRun writeGnss(const Simulator& sim, double duration_s, const std::string& dir) {
  const ScenarioParams& sp = sim.params();
  const GnssParams& p = sp.gnss;
  const gnss::EnuFrame enu({sp.origin_lat_deg, sp.origin_lon_deg, p.origin_h_m});
  std::mt19937_64 rng(sp.seed * 0x9E3779B97F4A7C15ULL + 23);
  std::normal_distribution<double> n01(0.0, 1.0);
  const double dt = 1.0 / p.rate_hz, t0 = static_cast<double>(sp.start_epoch_s);
  const double tunnel_a = sp.world.tunnel_start_m, tunnel_b = tunnel_a + sp.world.tunnel_length_m;
  const double bearing = p.multipath_bearing_deg * M_PI / 180;
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();
  std::string nmea, gt = "t,true_e,true_n,true_u,lat_deg,lon_deg,h_m,meas_e,meas_n,meas_u,state\n";
  GnssRun run;
  char line[400];
  const auto n = static_cast<std::size_t>(std::floor(duration_s * p.rate_hz + 1e-9));
  for (std::size_t k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) * dt;
    const VehicleState s = sim.trajectory().at(t);
    const Pose3 T_world_vehicle = Pose3::fromXyzYpr(s.x, s.y, s.z, s.yaw, s.pitch, s.roll);
    const Vec3 a = T_world_vehicle.apply({p.lever_x_m, p.lever_y_m, p.lever_z_m});
    const Eigen::Vector3d truth(a.x, a.y, a.z);
    // the noise is drawn every epoch, outage or not, so an outage does not shift the later noise
    const Eigen::Vector3d white(n01(rng) * p.noise_sigma_m, n01(rng) * p.noise_sigma_m, n01(rng) * p.noise_sigma_up_m);
    const double walk = p.bias_walk_m_per_sqrt_s * std::sqrt(dt);
    bias += Eigen::Vector3d(n01(rng), n01(rng), n01(rng)) * walk;
    const bool outage = (p.outage_in_tunnel && sp.world.tunnel_length_m > 0 && s.s_m >= tunnel_a && s.s_m <= tunnel_b) ||
                        (p.outage_duration_s > 0 && t >= p.outage_start_s && t < p.outage_start_s + p.outage_duration_s);
    const bool multipath = p.multipath_duration_s > 0 && t >= p.multipath_start_s &&
                           t < p.multipath_start_s + p.multipath_duration_s;
    Eigen::Vector3d meas = truth + white + bias;
    if (multipath) meas += p.multipath_offset_m * Eigen::Vector3d(std::sin(bearing), std::cos(bearing), 0);
    gnss::GnssFix f;
    f.t_receiver_s = t0 + t;
    f.time_of_day_s = std::fmod(f.t_receiver_s, 86400.0);
    f.has_position = !outage;
    f.position = enu.toGeodetic(meas);
    f.quality = outage ? 0 : 1;
    f.satellites = outage ? 0 : p.satellites;
    f.hdop = p.hdop;
    f.speed_mps = s.speed_mps;
    f.course_rad = std::fmod(2.5 * M_PI - s.yaw, 2 * M_PI);  // yaw from east, counter-clockwise
    f.sigma_lat_m = f.sigma_lon_m = std::max(0.01, p.noise_sigma_m);
    f.sigma_alt_m = std::max(0.01, p.noise_sigma_up_m);
    std::snprintf(line, sizeof(line), "%.6f ", t0 + t + p.latency_s);
    const std::string stamp = line;
    nmea += stamp + gnss::encodeRmc(f) + "\n" + stamp + gnss::encodeGga(f) + "\n";
    if (!outage) nmea += stamp + gnss::encodeVtg(f) + "\n" + stamp + gnss::encodeGst(f) + "\n";
    const gnss::Geodetic g = enu.toGeodetic(truth);
    std::snprintf(line, sizeof(line), "%.6f,%.4f,%.4f,%.4f,%.9f,%.9f,%.4f,%.4f,%.4f,%.4f,%s\n", t0 + t, truth.x(),
                  truth.y(), truth.z(), g.lat_deg, g.lon_deg, g.h_m, meas.x(), meas.y(), meas.z(),
                  outage ? "outage" : multipath ? "multipath" : "ok");
    gt += line;
    ++run.epochs;
    run.fixes += !outage;
    run.outage_epochs += outage;
    run.multipath_epochs += multipath && !outage;
  }
  writeFileAtomically(dir + "gnss.nmea", nmea);
  writeFileAtomically(dir + "gt_gnss.csv", gt);
  return run;
}

}  // namespace roadslam::sim
