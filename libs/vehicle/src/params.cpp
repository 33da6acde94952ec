#include <roadslam/common/config.h>
#include <roadslam/common/param_table.h>
#include <roadslam/vehicle/params.h>

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace roadslam::vehicle {
namespace {
constexpr double kG = 9.80665;  // standard gravity [m/s^2]
}  // namespace

const char* quantityKey(Quantity q) {
  static const char* kKeys[kQuantityCount] = {"wheel_fl",       "wheel_fr", "wheel_rl", "wheel_rr",
                                              "vehicle_speed",  "yaw_rate", "steering_angle", "accel_x",
                                              "accel_y",        "gear",     "latitude", "longitude",
                                              "gnss_height"};
  return kKeys[static_cast<int>(q)];
}

double unitScale(const std::string& u) {
  if (u == "mps" || u == "mps2" || u == "rad" || u == "rad_s" || u == "deg_wgs84" || u == "m" || u == "raw" || u.empty()) {
    return 1.0;
  }
  if (u == "kmh") return 1.0 / 3.6;
  if (u == "mph") return 0.44704;
  if (u == "deg" || u == "deg_s") return M_PI / 180.0;
  if (u == "g") return kG;
  if (u == "pct_g") return kG / 100.0;
  throw std::invalid_argument("unknown unit '" + u +
                              "' (accepted: mps kmh mph rad deg rad_s deg_s mps2 g pct_g deg_wgs84 m raw)");
}

std::string VehicleParams::dbcPath() const {
  if (dbc.empty() || std::filesystem::path(dbc).is_absolute() || data_root.empty()) return dbc;
  return (std::filesystem::path(data_root) / dbc).string();
}

std::vector<double> VehicleParams::reverseValues() const {
  std::vector<double> out;
  std::stringstream ss(reverse_gear_values);
  for (std::string tok; std::getline(ss, tok, ',');) {
    if (!tok.empty()) out.push_back(std::stod(tok));
  }
  return out;
}

void VehicleParams::fields(ParamTable& t) {
  t.text("name", name);
  t.text("dbc", dbc);
  t.text("data_root", data_root);
  t.text("interface", interface);
  t.num("wheelbase_m", wheelbase_m);
  t.num("track_width_m", track_width_m);
  t.num("steering_ratio", steering_ratio);
  t.text("reverse_gear_values", reverse_gear_values);
}

void VehicleParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  // The signal mapping of each quantity (five keys, saved only when mapped) is read by hand beside the table.
  std::vector<std::string> known = fieldKeys<VehicleParams>();
  for (int i = 0; i < kQuantityCount; ++i) {
    SignalMapping& m = map[static_cast<std::size_t>(i)];
    const std::string k = quantityKey(static_cast<Quantity>(i));
    m.signal = readString(cfg, s, k, m.signal);
    m.add_signal = readString(cfg, s, k + "_add", m.add_signal);
    m.negate_if = readString(cfg, s, k + "_negate_if", m.negate_if);
    m.unit = readString(cfg, s, k + "_unit", m.unit);
    m.sign = readDouble(cfg, s, k + "_sign", m.sign);
    try {
      m.unit_scale = unitScale(m.unit);
    } catch (const std::exception& e) {
      throw std::runtime_error("[" + s + "] " + k + "_unit: " + e.what());
    }
    if (m.sign != 1.0 && m.sign != -1.0) throw std::runtime_error("[" + s + "] " + k + "_sign must be 1 or -1");
    for (const char* suffix : {"", "_add", "_negate_if", "_unit", "_sign"}) known.push_back(k + suffix);
  }
  rejectUnknownKeys(cfg, s, known);
  if (wheelbase_m <= 0 || steering_ratio <= 0) {
    throw std::runtime_error("[" + s + "] wheelbase_m and steering_ratio must be positive");
  }
}

void VehicleParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
  for (int i = 0; i < kQuantityCount; ++i) {
    const SignalMapping& m = map[static_cast<std::size_t>(i)];
    if (!m.present()) continue;
    const std::string k = quantityKey(static_cast<Quantity>(i));
    cfg.write(s, k, m.signal);
    if (!m.add_signal.empty()) cfg.write(s, k + "_add", m.add_signal);
    if (!m.negate_if.empty()) cfg.write(s, k + "_negate_if", m.negate_if);
    cfg.write(s, k + "_unit", m.unit);
    cfg.write(s, k + "_sign", m.sign);
  }
}

VehicleParams loadVehicleIni(const std::string& path, const std::string& data_root) {
  const auto cfg = loadIniFile(path);
  VehicleParams p;
  try {
    p.loadFromConfigFile(*cfg, "vehicle");
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  if (!data_root.empty()) {
    p.data_root = data_root;
  } else if (!p.data_root.empty() && std::filesystem::path(p.data_root).is_relative()) {
    // An ini's own data_root is relative to the ini file, so it works from any working directory.
    p.data_root = (std::filesystem::path(path).parent_path() / p.data_root).lexically_normal().string();
  }
  if (p.dbc.empty()) throw std::runtime_error(path + ": [vehicle] dbc is required");
  if (!std::filesystem::is_regular_file(p.dbcPath())) {
    throw std::runtime_error(path + ": [vehicle] dbc = '" + p.dbc + "': no such file '" + p.dbcPath() + "'");
  }
  return p;
}

}  // namespace roadslam::vehicle
