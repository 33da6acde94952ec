#pragma once
/// \file gnss_output.h
/// The simulated GNSS receiver, section [gnss] of a scenario ini (off by default: with it
/// off the simulator writes exactly what it wrote before). The world frame is a local East-North-Up
/// frame whose origin is ([scenario] origin_lat_deg, origin_lon_deg, [gnss] origin_h_m) on WGS84.
/// At rate_hz the receiver reports its antenna (lever arm in the vehicle frame) through
/// GeographicLib's LocalCartesian, with the errors below, as NMEA 0183 epochs (RMC, GGA, VTG, GST,
/// one per line, each preceded by its receive time: libs/gnss/nmea.h's log format) in DIR/gnss.nmea,
/// and the truth per epoch in DIR/gt_gnss.csv.
///
/// Errors (east, north, up): white noise (noise_sigma_m horizontally, noise_sigma_up_m vertically) plus
/// a bias that random-walks (bias_walk_m_per_sqrt_s, per axis). Outages: no fix (GGA quality 0, RMC
/// 'V') in the world's tunnel (outage_in_tunnel) and in [outage_start_s, + outage_duration_s).
/// Multipath: in [multipath_start_s, + multipath_duration_s) the position jumps by multipath_offset_m
/// towards multipath_bearing_deg (clockwise from north), with the receiver unaware (GST unchanged).
/// Deterministic for the scenario seed.

#include <cstdint>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::sim {

class Simulator;

/// Section [gnss] of a scenario ini.
struct GnssParams {
  bool enabled = false;             ///< write DIR/gnss.nmea and DIR/gt_gnss.csv
  double rate_hz = 10;              ///< epochs per second, 1..20 [Hz]
  double origin_h_m = 500;          ///< world origin's height above the WGS84 ellipsoid [m]
  double lever_x_m = 0.5, lever_y_m = 0.0, lever_z_m = 1.7;  ///< antenna in the vehicle frame [m]
  double noise_sigma_m = 1.0;       ///< white noise, east and north, 1 sigma [m]
  double noise_sigma_up_m = 1.5;    ///< white noise, up [m]
  double bias_walk_m_per_sqrt_s = 0;  ///< bias random walk per axis [m/sqrt(s)]
  double latency_s = 0.05;          ///< receive time - receiver time [s]
  double hdop = 1.0;                ///< reported HDOP [-]
  int satellites = 10;              ///< reported satellites in use [-]
  bool outage_in_tunnel = true;     ///< no fix while the vehicle is in the world's tunnel
  double outage_start_s = 0, outage_duration_s = 0;  ///< a scripted outage [s]; duration 0 = none
  double multipath_start_s = 0, multipath_duration_s = 0;  ///< a scripted multipath jump [s]; 0 = none
  double multipath_offset_m = 50;   ///< size of the jump [m]
  double multipath_bearing_deg = 90;  ///< its direction, clockwise from north [deg] (ini _deg)

  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
  static std::vector<std::string> keys();
};

struct GnssRun {
  std::size_t epochs = 0, fixes = 0, outage_epochs = 0, multipath_epochs = 0;
};

/// Writes DIR/gnss.nmea and DIR/gt_gnss.csv for [0, duration_s] (\p dir ends with '/').
GnssRun writeGnss(const Simulator& sim, double duration_s, const std::string& dir);

}  // namespace roadslam::sim
