#include "roadslam/sim/trajectory.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::sim {

void TrajectoryParams::fields(ParamTable& t) {
  t.num("max_speed_kmh", max_speed_kmh);
  t.num("accel_mps2", accel_mps2);
  t.num("decel_mps2", decel_mps2);
  t.num("lateral_accel_mps2", lateral_accel_mps2);
  t.num("start_standing_s", start_standing_s);
  t.num("end_standing_s", end_standing_s);
  t.num("laps", laps);
  t.num("start_offset_m", start_offset_m);
  t.num("track_width_m", track_width_m);
  t.num("wheelbase_m", wheelbase_m);
  t.num("k_pitch_deg_per_mps2", k_pitch_deg_per_mps2);
  t.num("k_roll_deg_per_mps2", k_roll_deg_per_mps2);
}

void TrajectoryParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s) {
  loadFields(*this, c, s);
  if (track_width_m <= 0 || wheelbase_m <= 0 || std::abs(k_pitch_deg_per_mps2) > 2 || std::abs(k_roll_deg_per_mps2) > 2)
    throw std::runtime_error("[" + s + "] track_width_m, wheelbase_m must be > 0, |k_pitch_deg_per_mps2|, "
                             "|k_roll_deg_per_mps2| <= 2");
  if (max_speed_kmh <= 0 || accel_mps2 <= 0 || decel_mps2 <= 0 || lateral_accel_mps2 <= 0 || laps < 1)
    throw std::runtime_error("[" + s + "] max_speed_kmh, accel_mps2, decel_mps2, lateral_accel_mps2 "
                             "must be > 0 and laps >= 1");
  if (start_offset_m < 0) throw std::runtime_error("[" + s + "] start_offset_m must be >= 0");
}

void TrajectoryParams::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const {
  saveFields(*this, c, s);
}

std::vector<std::string> TrajectoryParams::keys() { return fieldKeys<TrajectoryParams>(); }

Road routeStartingAt(const Road& route, double start_offset_m) {
  if (!route.closed) throw std::runtime_error("[trajectory] start_offset_m needs a closed route (layout loop, or grid with an even number of streets)");
  const double len = roadLength(route);
  const double s0 = std::fmod(start_offset_m, len);
  // the dense centreline (0.5 m) restarts at its first point at or past s0
  const auto it = std::lower_bound(route.cum_m.begin(), route.cum_m.end(), s0);
  const auto k = static_cast<std::ptrdiff_t>(std::min<std::size_t>(it - route.cum_m.begin(), route.centerline.size() - 1));
  Road out = route;
  std::rotate(out.centerline.begin(), out.centerline.begin() + k, out.centerline.end());
  finalizeRoad(out);
  return out;
}

namespace {
/// Speed at each dense route point [m/s]: the curvature limit v^2 |k| <= a_lat, then a forward pass
/// (acceleration from standstill) and a backward pass (braking to standstill at the end).
std::vector<double> speedProfile(const std::vector<double>& s, const std::vector<double>& k,
                                 const TrajectoryParams& p) {
  const std::size_t m = s.size();
  std::vector<double> v(m);
  for (std::size_t j = 0; j < m; ++j)
    v[j] = std::min(p.max_speed_mps(), std::sqrt(p.lateral_accel_mps2 / std::max(1e-6, std::abs(k[j]))));
  v[0] = 0;
  for (std::size_t j = 1; j < m; ++j)
    v[j] = std::min(v[j], std::sqrt(v[j - 1] * v[j - 1] + 2 * p.accel_mps2 * (s[j] - s[j - 1])));
  v[m - 1] = 0;
  for (std::size_t j = m - 1; j-- > 0;)
    v[j] = std::min(v[j], std::sqrt(v[j + 1] * v[j + 1] + 2 * p.decel_mps2 * (s[j + 1] - s[j])));
  return v;
}
}  // namespace

Trajectory::Trajectory(const Road& route, const Ground& ground, const TrajectoryParams& p,
                       const World* surface)
    : ground_(ground), surface_(surface && surface->surface.any() ? surface : nullptr), p_(p), closed_(route.closed), route_len_(roadLength(route)) {
  // Dense route with smooth heading (mean of the adjacent segments) and curvature dh/ds.
  const auto& c = route.centerline;
  const std::size_t n = c.size();
  const int laps = closed_ ? p.laps : 1;
  const std::size_t m = closed_ ? n * laps + 1 : n;
  s_.resize(m);
  x_.resize(m);
  y_.resize(m);
  h_.resize(m);
  k_.resize(m);
  std::vector<double> seg(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = c[i], b = c[(i + 1) % n];
    seg[i] = (closed_ || i + 1 < n) ? std::atan2(b.y - a.y, b.x - a.x) : seg[i - 1];
  }
  for (std::size_t j = 0; j < m; ++j) {
    const std::size_t i = j % n;
    const double prev = (i == 0 && !closed_) ? seg[0] : seg[(i + n - 1) % n];
    const double d = std::remainder(seg[i] - prev, 2 * M_PI);
    x_[j] = c[i].x;
    y_[j] = c[i].y;
    s_[j] = (j < n ? route.cum_m[i] : route.cum_m[i] + route_len_ * static_cast<double>(j / n));
    h_[j] = j == 0 ? prev + 0.5 * d : h_[j - 1] + std::remainder(prev + 0.5 * d - h_[j - 1], 2 * M_PI);
  }
  for (std::size_t j = 0; j < m; ++j) {
    const std::size_t a = j > 0 ? j - 1 : j, b = j + 1 < m ? j + 1 : j;
    k_[j] = s_[b] > s_[a] ? (h_[b] - h_[a]) / (s_[b] - s_[a]) : 0;
  }
  const std::vector<double> v = speedProfile(s_, k_, p);
  std::vector<double> t(m);
  t[0] = p.start_standing_s;
  for (std::size_t j = 1; j < m; ++j) t[j] = t[j - 1] + 2 * (s_[j] - s_[j - 1]) / std::max(1e-9, v[j - 1] + v[j]);
  duration_ = t[m - 1] + p.end_standing_s;
  // 10 ms table: constant acceleration within each dense segment.
  const std::size_t steps = static_cast<std::size_t>(std::floor(duration_ / kStep_s)) + 1;
  states_.reserve(steps);
  std::size_t j = 0;
  for (std::size_t k = 0; k < steps; ++k) {
    const double tk = k * kStep_s;
    while (j + 2 < m && t[j + 1] <= tk) ++j;
    double s = 0, vk = 0, ak = 0;
    if (tk <= t[0]) {
      s = 0;
    } else if (tk >= t[m - 1]) {
      s = s_[m - 1];
    } else {
      const double ds = s_[j + 1] - s_[j];
      ak = (v[j + 1] * v[j + 1] - v[j] * v[j]) / (2 * ds);
      const double tau = tk - t[j];
      s = s_[j] + v[j] * tau + 0.5 * ak * tau * tau;
      vk = v[j] + ak * tau;
    }
    VehicleState st = stateAtArcLength(s, vk, ak);
    st.t_s = tk;
    states_.push_back(st);
  }
}

VehicleState Trajectory::stateAtArcLength(double s, double v, double a) const {
  auto it = std::upper_bound(s_.begin(), s_.end(), s);
  std::size_t i = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(it - s_.begin(), 1, s_.size() - 1));
  const double f = std::clamp((s - s_[i - 1]) / std::max(1e-9, s_[i] - s_[i - 1]), 0.0, 1.0);
  VehicleState st;
  st.s_m = s;
  st.x = x_[i - 1] + f * (x_[i] - x_[i - 1]);
  st.y = y_[i - 1] + f * (y_[i] - y_[i - 1]);
  st.z = ground_.height(st.x, st.y);
  st.yaw = std::remainder(h_[i - 1] + f * (h_[i] - h_[i - 1]), 2 * M_PI);
  const double kappa = k_[i - 1] + f * (k_[i] - k_[i - 1]);
  const Vec2 g = ground_.gradient(st.x, st.y);
  const double ch = std::cos(st.yaw), sh = std::sin(st.yaw);
  st.pitch = 0.0 - std::atan(g.x * ch + g.y * sh);  // (no -0) nose up on an uphill (ZYX: +pitch is nose down)
  st.roll = std::atan(-g.x * sh + g.y * ch);   // left side up when the ground rises to the left
  if (surface_) {
    // Wheel contacts on the crown (World::crownOffset: the suspension keeps the short-wavelength
    // roughness from the body): the rear axle's mean sets the reference height, the left/right and
    // front/rear differences tilt the body.
    const double hw = 0.5 * p_.track_width_m, L = p_.wheelbase_m;
    auto off = [&](double along, double left) {
      return surface_->crownOffset(st.x + along * ch - left * sh, st.y + along * sh + left * ch);
    };
    const double rl = off(0, hw), rr = off(0, -hw), fl = off(L, hw), fr = off(L, -hw);
    st.z += 0.5 * (rl + rr);
    st.roll += std::atan(0.5 * ((rl + fl) - (rr + fr)) / p_.track_width_m);
    st.pitch -= std::atan(0.5 * ((fl + fr) - (rl + rr)) / L);
  }
  // Suspension: pitch and roll proportional to the accelerations (ZYX: +pitch nose down, +roll
  // left side up; a left turn's lateral acceleration v^2 kappa > 0 rolls the body to the right).
  constexpr double kDeg = M_PI / 180.0;
  if (p_.k_pitch_deg_per_mps2 != 0) st.pitch -= p_.k_pitch_deg_per_mps2 * kDeg * a;
  if (p_.k_roll_deg_per_mps2 != 0) st.roll += p_.k_roll_deg_per_mps2 * kDeg * v * v * kappa;
  st.speed_mps = v;
  st.accel_mps2 = a;
  st.yaw_rate_rps = v * kappa;
  st.wheel_speed_left_mps = v * (1 - 0.5 * kappa * p_.track_width_m);
  st.wheel_speed_right_mps = v * (1 + 0.5 * kappa * p_.track_width_m);
  return st;
}

VehicleState Trajectory::at(double t_s) const {
  const double u = std::clamp(t_s / kStep_s, 0.0, static_cast<double>(states_.size() - 1));
  const std::size_t i = std::min(static_cast<std::size_t>(u), states_.size() - 2);
  const double f = u - static_cast<double>(i);
  const VehicleState& a = states_[i];
  const VehicleState& b = states_[i + 1];
  auto lerp = [f](double p, double q) { return p + f * (q - p); };
  VehicleState s = a;
  s.t_s = t_s;
  s.x = lerp(a.x, b.x);
  s.y = lerp(a.y, b.y);
  s.z = lerp(a.z, b.z);
  s.yaw = a.yaw + f * std::remainder(b.yaw - a.yaw, 2 * M_PI);
  s.pitch = lerp(a.pitch, b.pitch);
  s.roll = lerp(a.roll, b.roll);
  s.speed_mps = lerp(a.speed_mps, b.speed_mps);
  s.yaw_rate_rps = lerp(a.yaw_rate_rps, b.yaw_rate_rps);
  s.s_m = lerp(a.s_m, b.s_m);
  return s;
}

}  // namespace roadslam::sim
