#include "roadslam/sim/can_output.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "roadslam/can/dbc.h"
#include "roadslam/can/encoder.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "roadslam/sim/simulator.h"

namespace roadslam::sim {
namespace {
using unit::kDeg;
using unit::kKmh;
constexpr int kGearDrive = 3;  // VAL_ 944 GEAR 3 "D"
constexpr double kStillMps = 1e-3;  // below this a wheel does not turn [m/s]

/// One DBC message sent every period_steps trajectory steps, phase_us after the step.
struct Stream {
  can::MessageEncoder enc;
  int period_steps;
  int64_t phase_us;
  std::vector<double> v;
  int counter = 0;
};

Stream makeStream(const can::Database& db, const std::string& dbc, const char* name, int period_steps,
                  int64_t phase_us) {
  const can::Message* m = db.findMessage(std::string(name));
  if (!m) throw std::runtime_error(dbc + ": message " + name + " missing (needed by the CAN simulation)");
  Stream s{can::MessageEncoder(*m), period_steps, phase_us, {}};
  s.v.assign(s.enc.size(), std::nan(""));
  return s;
}

/// The quantities one step reports, with the sensor errors applied (SI units).
struct Measured {
  double wheel[4];  // FL FR RL RR [m/s]
  double speed, yaw_rate, ax, ay, steer;
};
}  // namespace

std::string CanParams::dbcPath() const { return dbc.empty() ? std::string(ROADSLAM_SIM_DBC) : dbc; }

std::vector<std::string> CanParams::keys() { return fieldKeys<CanParams>(); }

void CanParams::fields(ParamTable& t) {
  t.flag("enabled", enabled);
  t.text("dbc", dbc);
  t.text("interface", interface);
  t.angle("yaw_rate_bias_deg_s", yaw_rate_bias_radps);
  t.angle("yaw_rate_noise_deg_s", yaw_rate_noise_radps);
  t.num("wheel_speed_scale_error", wheel_speed_scale_error);
  t.scaled("wheel_speed_noise_kmh", wheel_speed_noise_mps, unit::kKmh);
  t.num("accel_noise_mps2", accel_noise_mps2);
  t.angle("steering_noise_deg", steering_noise_rad);
  t.num("wheelbase_m", wheelbase_m);
  t.num("steering_ratio", steering_ratio);
}

void CanParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section) {
  loadFields(*this, cfg, section);
  if (yaw_rate_noise_radps < 0 || wheel_speed_noise_mps < 0 || accel_noise_mps2 < 0 || steering_noise_rad < 0)
    throw std::runtime_error("[" + section + "] noise sigmas must be >= 0");
  if (wheelbase_m <= 0 || steering_ratio <= 0)
    throw std::runtime_error("[" + section + "] wheelbase_m and steering_ratio must be > 0");
}

void CanParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const {
  saveFields(*this, cfg, section);
}

std::vector<can::CanFrame> simulateCan(const Simulator& sim, double duration_s) {
  return simulateCan(sim, sim.params().can, sim.params().seed, duration_s);
}

std::vector<can::CanFrame> simulateCan(const Simulator& sim, const CanParams& p, uint64_t seed, double duration_s) {
  const std::string path = p.dbcPath();
  const can::Database db = can::loadDbcFile(path);
  // Phases: the ECUs are not synchronised with each other nor with the lidar.
  std::vector<Stream> st;
  st.push_back(makeStream(db, path, "WHEEL_SPEEDS", 1, 300));
  st.push_back(makeStream(db, path, "YAW_RATE", 1, 2100));
  st.push_back(makeStream(db, path, "VEHICLE_SPEED", 2, 5400));
  st.push_back(makeStream(db, path, "STEERING", 2, 7700));
  st.push_back(makeStream(db, path, "GEAR", 10, 4900));
  auto idx = [&](std::size_t s, const char* sig) { return st[s].enc.index(sig); };
  const std::size_t iw[4] = {idx(0, "WHEEL_SPEED_FL"), idx(0, "WHEEL_SPEED_FR"), idx(0, "WHEEL_SPEED_RL"),
                             idx(0, "WHEEL_SPEED_RR")};
  const std::size_t iyaw = idx(1, "YAW_RATE"), iax = idx(1, "ACCEL_X"), iay = idx(1, "ACCEL_Y");
  const std::size_t ispeed = idx(2, "VEHICLE_SPEED"), istand = idx(2, "STANDSTILL");
  const std::size_t isteer = idx(3, "STEER_ANGLE"), igear = idx(4, "GEAR");

  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ULL + 0xCA);
  std::normal_distribution<double> n01(0.0, 1.0);
  const double tw = sim.params().trajectory.track_width_m, L = p.wheelbase_m;
  const int64_t t0_us = sim.params().start_epoch_s * 1000000;
  const auto n_steps = static_cast<int64_t>(std::floor(duration_s / Trajectory::kStep_s + 1e-9));
  double road_wheel = 0;  // held while standing (the steering is not observable from the motion)
  std::vector<can::CanFrame> out;
  out.reserve(static_cast<std::size_t>(n_steps + 1) * 3);
  const double scale = 1 + p.wheel_speed_scale_error;
  for (int64_t i = 0; i <= n_steps; ++i) {
    const double t = static_cast<double>(i) * Trajectory::kStep_s;
    const VehicleState s = sim.trajectory().at(t);
    const double v = s.speed_mps, w = s.yaw_rate_rps;
    if (v > 0.5) road_wheel = std::atan(L * w / v);  // kinematic bicycle model
    // Rear wheels at (0, +-tw/2), front wheels at (L, +-tw/2) in the vehicle frame: |v + w x r|.
    const double true_wheel[4] = {std::hypot(v - w * tw / 2, w * L), std::hypot(v + w * tw / 2, w * L),
                                  std::abs(v - w * tw / 2), std::abs(v + w * tw / 2)};
    // A wheel that does not turn gives no sensor pulses: exactly 0, never noise.
    auto wheel = [&](double truth) {
      const double noisy = std::max(0.0, truth * scale + p.wheel_speed_noise_mps * n01(rng));
      return truth < kStillMps ? 0.0 : noisy / kKmh;
    };
    auto& ws = st[0].v;
    for (int k = 0; k < 4; ++k) ws[iw[k]] = wheel(true_wheel[k]);
    st[1].v[iyaw] = (w + p.yaw_rate_bias_radps + p.yaw_rate_noise_radps * n01(rng)) / kDeg;
    st[1].v[iax] = s.accel_mps2 + p.accel_noise_mps2 * n01(rng);
    st[1].v[iay] = v * w + p.accel_noise_mps2 * n01(rng);
    st[2].v[ispeed] = wheel(v);
    st[2].v[istand] = v < 0.01 ? 1 : 0;
    st[3].v[isteer] = (p.steering_ratio * road_wheel + p.steering_noise_rad * n01(rng)) / kDeg;
    st[4].v[igear] = kGearDrive;
    for (Stream& m : st) {
      if (i % m.period_steps != 0) continue;
      if (m.enc.message().findSignal("COUNTER")) m.v[m.enc.index("COUNTER")] = m.counter;
      m.counter = (m.counter + 1) % 16;
      can::CanFrame f;
      m.enc.encode(m.v.data(), t0_us + i * 10000 + m.phase_us, f);
      f.setInterface(p.interface.c_str());
      out.push_back(f);
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const can::CanFrame& a, const can::CanFrame& b) { return a.t_us < b.t_us; });
  return out;
}

}  // namespace roadslam::sim
