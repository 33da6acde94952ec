#pragma once
/// \file params.h
/// Which DBC signals carry a car's vehicle-dynamics quantities, in which units, plus the car's
/// geometry. Loaded from an ini section (ini/vehicles/<car>.ini, section [vehicle]):
///
///     dbc = can/rav4-2017/toyota_new_mc_pt_generated.dbc  ; relative to data_root (or absolute)
///     wheel_fl = WHEEL_SPEEDS.WHEEL_SPEED_FL               ; MESSAGE.SIGNAL
///     wheel_fl_unit = kmh                                  ; kmh mps mph deg_s rad_s deg rad mps2 g
///     yaw_rate_sign = 1                                    ; multiply to get CCW-positive (ISO 8855)
///     steering_angle_add = STEER_ANGLE_SENSOR.STEER_FRACTION  ; optional second signal, summed
///     steering_angle_negate_if = LWI_01.LWI_VZ_Lenkradwinkel  ; optional sign-flag signal (1 = negative)

#include <array>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::vehicle {

/// The quantities a car may report. Frames: vehicle body, x forward, y left, z up (ISO 8855).
enum class Quantity : int {
  kWheelFL, kWheelFR, kWheelRL, kWheelRR,  ///< wheel speeds [m/s]
  kVehicleSpeed,                          ///< [m/s]
  kYawRate,                               ///< [rad/s], CCW positive
  kSteeringAngle,                         ///< steering-wheel angle [rad], left positive
  kAccelX, kAccelY,                       ///< longitudinal / lateral acceleration [m/s^2]
  kGear,                                  ///< raw gear value (no unit)
  kLatitude, kLongitude,                  ///< WGS84 [deg]
  kGnssHeight,                            ///< GNSS height [m] (the car's own reference: ellipsoid or sea level)
  kCount
};
constexpr int kQuantityCount = static_cast<int>(Quantity::kCount);
/// Ini key stem of a quantity ("wheel_fl", "yaw_rate", ...).
const char* quantityKey(Quantity q);

/// How one quantity is read: value = sign * unit_scale * (signal + add_signal), negated when the
/// negate_if signal decodes non-zero.
struct SignalMapping {
  std::string signal;       ///< "MESSAGE.SIGNAL"; empty = the car does not report it
  std::string add_signal;   ///< optional second signal summed before scaling (same unit)
  std::string negate_if;    ///< optional sign-flag signal
  std::string unit;         ///< unit name as in the ini
  double unit_scale = 1.0;  ///< SI value of one ini unit (kmh -> 1/3.6)
  double sign = 1.0;        ///< +1 or -1 to reach the ISO 8855 sign convention
  bool present() const { return !signal.empty(); }
};

/// SI value of one unit name; throws std::invalid_argument listing the accepted names.
double unitScale(const std::string& unit);

struct VehicleParams {
  std::string name;                 ///< car name for reports
  std::string dbc;                  ///< DBC path, relative to data_root unless absolute
  std::string data_root;            ///< folder DBC paths are relative to (ini: relative to the ini file)
  std::string interface;            ///< only frames from this interface ("can0"); empty = all
  double wheelbase_m = 2.7;         ///< [m] front to rear axle
  double track_width_m = 1.6;       ///< [m] (rear) track width, for yaw rate from wheel speeds
  double steering_ratio = 16.0;     ///< steering-wheel angle / road-wheel angle [-]
  std::string reverse_gear_values;  ///< comma-separated raw gear values meaning reverse
  std::array<SignalMapping, kQuantityCount> map;

  const SignalMapping& at(Quantity q) const { return map[static_cast<std::size_t>(q)]; }
  /// DBC path with data_root applied.
  std::string dbcPath() const;
  std::vector<double> reverseValues() const;

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Throws std::runtime_error naming the section/key on a bad value or unknown unit.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

/// Loads [vehicle] from an ini file; \p data_root (if not empty) overrides the ini's data_root,
/// which, when relative, is relative to the ini file's folder.
/// Throws naming the file.
VehicleParams loadVehicleIni(const std::string& path, const std::string& data_root = "");

}  // namespace roadslam::vehicle
