#pragma once
/// \file trajectory.h
/// The vehicle's drive along the route: a speed profile limited by the maximum speed, longitudinal
/// acceleration/deceleration and lateral acceleration in curves, standing still at the start and end.
/// States every 10 ms carry everything a CAN simulation needs (speed, yaw rate, wheel speeds).
/// Vehicle frame: x forward, y left, z up; origin on the ground below the rear axle centre.

#include <string>
#include <vector>

#include "roadslam/sim/world.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::sim {

struct TrajectoryParams {
  double max_speed_kmh = 50;         ///< [km/h]
  double accel_mps2 = 1.5;           ///< longitudinal acceleration limit [m/s^2]
  double decel_mps2 = 2.0;           ///< braking limit [m/s^2]
  double lateral_accel_mps2 = 2.5;   ///< v^2 * curvature limit in turns [m/s^2]
  double start_standing_s = 2.0;     ///< standing still before driving off [s]
  double end_standing_s = 1.0;       ///< standing still after arriving [s]
  int laps = 1;                      ///< closed routes: number of laps [-]
  /// Closed routes: the drive starts (and ends) this far along the route from the layout's start,
  /// in the same direction (another drive of the same streets from another start) [m]
  double start_offset_m = 0;
  double track_width_m = 1.6;        ///< for the wheel speeds and the wheel contacts [m]
  double wheelbase_m = 2.7;          ///< rear to front axle, for the wheel contacts on a rough road [m]
  /// Suspension (both 0 = rigid): body pitch = -k_pitch * longitudinal acceleration (nose down when
  /// braking), body roll = k_roll * lateral acceleration (leaning out of the turn); real motion of
  /// the sensor, so in the ground truth [deg per m/s^2].
  double k_pitch_deg_per_mps2 = 0;
  double k_roll_deg_per_mps2 = 0;

  double max_speed_mps() const { return max_speed_kmh / 3.6; }
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
  static std::vector<std::string> keys();
};

/// \p route (closed, finalized) restarting at its centreline point nearest past \p start_offset_m
/// (modulo its length) [m]; throws on an open route, naming the key.
Road routeStartingAt(const Road& route, double start_offset_m);

/// Vehicle state at time t: pose of the vehicle frame in the world frame (T_world_vehicle as
/// translation + ZYX Euler angles) and its motion.
struct VehicleState {
  double t_s = 0;                    ///< time since the start of the simulation [s]
  double x = 0, y = 0, z = 0;        ///< [m] world frame
  double yaw = 0, pitch = 0, roll = 0;  ///< ZYX Euler angles [rad]
  double speed_mps = 0;              ///< forward speed [m/s]
  double accel_mps2 = 0;             ///< forward acceleration [m/s^2]
  double yaw_rate_rps = 0;           ///< [rad/s]
  double wheel_speed_left_mps = 0, wheel_speed_right_mps = 0;  ///< rear wheels [m/s]
  double s_m = 0;                    ///< distance driven [m]
};

class Trajectory {
 public:
  static constexpr double kStep_s = 0.01;  ///< state table period [s]

  /// \p surface: when given, the car stands on its surfaceHeight (crown, roughness): its four wheel
  /// contacts set the height, pitch and roll on top of the Ground's.
  Trajectory(const Road& route, const Ground& ground, const TrajectoryParams& p,
             const World* surface = nullptr);
  /// Time from the start until the vehicle has stood for end_standing_s at the end [s].
  double duration_s() const { return duration_; }
  double distance_m() const { return states_.empty() ? 0 : states_.back().s_m; }
  /// States every kStep_s from t = 0 to duration_s().
  const std::vector<VehicleState>& states() const { return states_; }
  /// State at any t (linear interpolation of the 10 ms table; clamped to [0, duration]).
  VehicleState at(double t_s) const;

 private:
  VehicleState stateAtArcLength(double s, double v, double a) const;
  const Ground& ground_;
  const World* surface_;
  TrajectoryParams p_;
  bool closed_ = false;
  double route_len_ = 0;
  std::vector<double> s_, x_, y_, h_, k_;  ///< dense route: arc length, position, heading, curvature
  std::vector<VehicleState> states_;
  double duration_ = 0;
};

}  // namespace roadslam::sim
