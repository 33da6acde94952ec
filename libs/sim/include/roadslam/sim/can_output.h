#pragma once
/// \file can_output.h
/// The simulated car's CAN traffic: the trajectory states encoded with a DBC (by default our own
/// ini/vehicles/roadslam-sim.dbc) into candump frames stamped on the capture clock of the pcap
/// (t = 0 is ScenarioParams::start_epoch_s). Messages and rates of roadslam-sim.dbc:
///   WHEEL_SPEEDS 100 Hz (4 wheels), YAW_RATE 100 Hz (yaw rate, long/lat acceleration),
///   VEHICLE_SPEED 50 Hz, STEERING 50 Hz (steering-wheel angle), GEAR 10 Hz.
/// Sensor errors: a constant yaw-rate bias plus white noise, a wheel-speed scale error plus white
/// noise, acceleration and steering noise; then the DBC's quantisation. Deterministic for a seed.

#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/can/frame.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::sim {

class Simulator;

/// Section [can] of a scenario ini.
struct CanParams {
  bool enabled = true;                  ///< write DIR/can.log
  std::string dbc;                      ///< DBC file; empty = the shipped roadslam-sim.dbc
  std::string interface = "can0";       ///< candump interface name
  double yaw_rate_bias_radps = 0.3 * 3.14159265358979323846 / 180;  ///< gyro bias [rad/s] (ini _deg_s)
  double yaw_rate_noise_radps = 0.05 * 3.14159265358979323846 / 180;  ///< white noise sigma [rad/s] (ini _deg_s)
  double wheel_speed_scale_error = 0.005;  ///< reported / true wheel speed - 1 [-] (tyre radius error)
  double wheel_speed_noise_mps = 0.03 / 3.6;  ///< white noise sigma [m/s] (ini _kmh)
  double accel_noise_mps2 = 0.02;       ///< white noise sigma of both accelerations [m/s^2]
  double steering_noise_rad = 0.1 * 3.14159265358979323846 / 180;  ///< sigma [rad] (ini _deg)
  double wheelbase_m = 2.7;             ///< front to rear axle, for front wheels and steering [m]
  double steering_ratio = 16.0;         ///< steering-wheel / road-wheel angle [-]

  /// DBC path actually used (dbc, or the shipped one).
  std::string dbcPath() const;
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
  static std::vector<std::string> keys();
};

/// CAN frames of the drive over [0, duration_s], in time order. Throws naming the DBC when it
/// cannot be read or lacks a message/signal of the list above. Noise seeded from the scenario seed.
std::vector<can::CanFrame> simulateCan(const Simulator& sim, double duration_s);
/// As above with explicit parameters and seed.
std::vector<can::CanFrame> simulateCan(const Simulator& sim, const CanParams& p, uint64_t seed, double duration_s);

}  // namespace roadslam::sim
