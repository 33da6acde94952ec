#include <roadslam/common/atomic_file.h>
#include <roadslam/vehicle/can_odometry.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

namespace roadslam::vehicle {
namespace {
constexpr double kEarthRadius = 6378137.0;  // WGS84 semi-major axis [m]

// Integrated speed and yaw-rate angle of the samples up to time t (piecewise constant, held
// from each sample to the next).
struct Integrator {
  std::vector<double> t, dist, angle;
  explicit Integrator(const std::vector<MotionSample>& s) {
    double d = 0, a = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (i > 0) {
        const double dt = s[i].t_s - s[i - 1].t_s;
        d += std::abs(s[i].speed_mps) * dt;
        a += s[i].yaw_rate_radps * dt;
      }
      t.push_back(s[i].t_s);
      dist.push_back(d);
      angle.push_back(a);
    }
  }
  bool covers(double x) const { return !t.empty() && x >= t.front() && x <= t.back(); }
  static double interp(const std::vector<double>& tt, const std::vector<double>& v, double x) {
    const auto it = std::lower_bound(tt.begin(), tt.end(), x);
    if (it == tt.begin()) return v.front();
    if (it == tt.end()) return v.back();
    const std::size_t i = static_cast<std::size_t>(it - tt.begin());
    const double f = (x - tt[i - 1]) / (tt[i] - tt[i - 1]);
    return v[i - 1] + f * (v[i] - v[i - 1]);
  }
  double distanceAt(double x) const { return interp(t, dist, x); }
  double angleAt(double x) const { return interp(t, angle, x); }
};
}  // namespace

OdometryResult runOdometry(const std::vector<can::CanFrame>& frames, VehicleDecoder& decoder,
                           const DeadReckoningParams& params, const Pose2D& start) {
  OdometryResult r;
  DeadReckoning dr(params, decoder.params());
  bool started = false;
  VehicleState state;
  for (const can::CanFrame& f : frames) {
    const UpdateMask mask = decoder.process(f, state);
    if (!mask) continue;
    if (!started && (mask & (kWheelMask | bit(Quantity::kVehicleSpeed)))) {
      Pose2D s = start;
      s.t_s = state.t_s;
      dr.reset(s);
      started = true;
      r.poses.push_back(s);
    }
    if (!started) continue;
    if (dr.update(state, mask)) r.poses.push_back(dr.pose());
    if (mask & (kWheelMask | bit(Quantity::kVehicleSpeed))) {
      MotionSample m;
      m.t_s = state.t_s;
      m.speed_mps = (state.reverse ? -1.0 : 1.0) * state.speed();
      m.has_yaw_rate = state.has(Quantity::kYawRate);
      m.yaw_rate_radps = m.has_yaw_rate ? state.value(Quantity::kYawRate) : 0.0;
      r.samples.push_back(m);
    }
  }
  r.decode = decoder.stats();
  r.dead_reckoning = dr.stats();
  r.yaw_rate_bias_radps = dr.yawRateBias();
  return r;
}

std::vector<gnss::GnssFix> loadGnssFixCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open GNSS fix file '" + path + "'");
  std::string line;
  std::getline(in, line);
  std::map<std::string, std::size_t> col;
  {
    std::stringstream ss(line);
    std::size_t i = 0;
    for (std::string c; std::getline(ss, c, ',');) col[c] = i++;
  }
  for (const char* need : {"t_unix", "lat_deg", "lon_deg", "speed_mps", "bearing_deg"}) {
    if (!col.count(need)) throw std::runtime_error(path + ":1: missing column '" + need + "'");
  }
  std::vector<gnss::GnssFix> out;
  for (std::size_t ln = 2; std::getline(in, line); ++ln) {
    std::vector<std::string> c;
    std::stringstream ss(line);
    for (std::string tok; std::getline(ss, tok, ',');) c.push_back(tok);
    try {
      gnss::GnssFix f;
      f.t_receiver_s = f.t_receive_s = std::stod(c.at(col["t_unix"]));
      f.position.lat_deg = std::stod(c.at(col["lat_deg"]));
      f.position.lon_deg = std::stod(c.at(col["lon_deg"]));
      f.has_position = true;
      f.rmc_status = 'A';
      f.speed_mps = std::stod(c.at(col["speed_mps"]));
      f.course_rad = std::stod(c.at(col["bearing_deg"])) * M_PI / 180.0;
      out.push_back(f);
    } catch (const std::exception&) {
      throw std::runtime_error(path + ":" + std::to_string(ln) + ": malformed GNSS fix line");
    }
  }
  return out;
}

ScaleEstimate estimateSpeedScale(const std::vector<MotionSample>& samples, const std::vector<gnss::GnssFix>& fixes,
                                 double min_speed_mps) {
  ScaleEstimate e;
  const Integrator integ(samples);
  for (std::size_t i = 1; i < fixes.size(); ++i) {
    const gnss::Geodetic& a = fixes[i - 1].position;
    const gnss::Geodetic& b = fixes[i].position;
    const double ta = fixes[i - 1].stamp(), tb = fixes[i].stamp();
    if (!integ.covers(ta) || !integ.covers(tb)) continue;
    if (fixes[i - 1].speed_mps < min_speed_mps || fixes[i].speed_mps < min_speed_mps) continue;
    const double lat = 0.5 * (a.lat_deg + b.lat_deg) * M_PI / 180.0;
    const double dn = (b.lat_deg - a.lat_deg) * M_PI / 180.0 * kEarthRadius;
    const double de = (b.lon_deg - a.lon_deg) * M_PI / 180.0 * kEarthRadius * std::cos(lat);
    e.gnss_m += std::hypot(de, dn);
    e.wheels_m += integ.distanceAt(tb) - integ.distanceAt(ta);
    ++e.intervals;
  }
  if (e.wheels_m > 0) e.scale = e.gnss_m / e.wheels_m;
  return e;
}

BiasEstimate estimateYawRateBias(const std::vector<MotionSample>& samples, const std::vector<gnss::GnssFix>& fixes,
                                 double min_speed_mps) {
  BiasEstimate e;
  const Integrator integ(samples);
  std::vector<double> ts, ds;
  double prev = 0, unwrapped = 0;
  bool first = true;
  for (const gnss::GnssFix& f : fixes) {
    if (f.speed_mps < min_speed_mps || !integ.covers(f.stamp())) continue;
    const double heading = M_PI / 2 - f.course_rad;  // ENU: CCW from east
    if (first) {
      unwrapped = heading;
      first = false;
    } else {
      unwrapped += std::remainder(heading - prev, 2 * M_PI);
    }
    prev = heading;
    ts.push_back(f.stamp() - fixes.front().stamp());
    ds.push_back(integ.angleAt(f.stamp()) - unwrapped);
  }
  e.fixes = ts.size();
  if (ts.size() < 3) return e;
  // Least-squares slope of d(t) = c + bias * t.
  double mt = 0, md = 0;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    mt += ts[i];
    md += ds[i];
  }
  mt /= static_cast<double>(ts.size());
  md /= static_cast<double>(ts.size());
  double num = 0, den = 0;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    num += (ts[i] - mt) * (ds[i] - md);
    den += (ts[i] - mt) * (ts[i] - mt);
  }
  if (den > 0) e.bias_radps = num / den;
  return e;
}

void writeTum(const std::string& path, const std::vector<Pose2D>& poses) {
  AtomicFile f(path);
  std::ostream& o = f.stream();
  o << std::fixed;
  for (const Pose2D& p : poses) {
    o << std::setprecision(6) << p.t_s << ' ' << std::setprecision(4) << p.x_m << ' ' << p.y_m << " 0 0 0 "
      << std::setprecision(9) << std::sin(p.yaw_rad / 2) << ' ' << std::cos(p.yaw_rad / 2) << '\n';
  }
  f.commit();
}

}  // namespace roadslam::vehicle
