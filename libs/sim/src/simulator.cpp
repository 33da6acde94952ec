#include "roadslam/sim/simulator.h"

#include "roadslam/common/stop_signal.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <stdexcept>

#include "roadslam/common/checked_config.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "roadslam/velodyne/encoder.h"

namespace roadslam::sim {

namespace {
/// Followed traffic is integrated this far past the drive: the outputs sample up to its end (and a
/// test's central differences a little beyond) [s].
constexpr double kTrafficMargin_s = 10.0;

/// Keys of \p section that no parameter reads: an error in every program's words (checked_config.h:
/// "FILE:LINE: unknown key 'K' in [S] (nearest known: N)"), or with \p unknown a warning appended there.
void rejectUnknown(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                   const std::vector<std::string>& known, std::vector<std::string>* unknown) {
  const auto* file = dynamic_cast<const CheckedConfig*>(&cfg);
  for (const auto& key : unknownKeys(cfg, section, known)) {
    const int line = file ? file->lineOf(section, key) : 0;
    const std::string near = nearestName(key, known);
    const std::string where = file ? file->path() + (line > 0 ? ":" + std::to_string(line) : "") + ": " : "";
    const std::string msg = where + "unknown key '" + key + "' in [" + section + "]" +
                            (near.empty() ? "" : " (nearest known: " + near + ")");
    if (!unknown) throw std::runtime_error(msg);
    unknown->push_back(msg);
  }
}
}  // namespace

void ScenarioParams::fields(ParamTable& t) {
  t.text("name", name);
  int seed_value = static_cast<int>(seed);
  t.num("seed", seed_value);
  if (t.loading() && seed_value < 0) throw std::runtime_error("[scenario] seed must be >= 0");
  seed = static_cast<uint64_t>(seed_value);
  t.num("duration_s", duration_s);
  t.num("start_epoch_s", start_epoch_s);
  t.flag("position_packets", position_packets);
  t.num("origin_lat_deg", origin_lat_deg);
  t.num("origin_lon_deg", origin_lon_deg);
}

void ScenarioParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, std::vector<std::string>* unknown) {
  std::vector<std::string> sections;
  cfg.getAllSections(sections);
  for (const auto& s : sections)
    if (s != "scenario" && s != "world" && s != "trajectory" && s != "lidar" && s != "can" && s != "gnss")
      throw std::runtime_error("unknown section [" + s + "] (expected scenario, world, trajectory, lidar, can, gnss)");
  rejectUnknown(cfg, "scenario", fieldKeys<ScenarioParams>(), unknown);
  rejectUnknown(cfg, "world", WorldParams::keys(), unknown);
  rejectUnknown(cfg, "trajectory", TrajectoryParams::keys(), unknown);
  rejectUnknown(cfg, "lidar", LidarParams::keys(), unknown);
  rejectUnknown(cfg, "can", CanParams::keys(), unknown);
  rejectUnknown(cfg, "gnss", GnssParams::keys(), unknown);
  loadFields(*this, cfg, "scenario");
  if (duration_s < 0) throw std::runtime_error("[scenario] duration_s must be >= 0");
  world.loadFromConfigFile(cfg, "world");
  trajectory.loadFromConfigFile(cfg, "trajectory");
  lidar.loadFromConfigFile(cfg, "lidar");
  can.loadFromConfigFile(cfg, "can");
  gnss.loadFromConfigFile(cfg, "gnss");
}

void ScenarioParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const {
  saveFields(*this, cfg, "scenario");
  world.saveToConfigFile(cfg, "world");
  trajectory.saveToConfigFile(cfg, "trajectory");
  lidar.saveToConfigFile(cfg, "lidar");
  can.saveToConfigFile(cfg, "can");
  if (gnss.enabled) gnss.saveToConfigFile(cfg, "gnss");
}

ScenarioParams ScenarioParams::fromFile(const std::string& path, std::vector<std::string>* unknown) {
  const auto cfg = loadIniFile(path);
  ScenarioParams p;
  try {
    p.loadFromConfigFile(*cfg, unknown);
  } catch (const std::exception& e) {
    const std::string what = e.what();
    throw std::runtime_error(what.find(path) == std::string::npos ? path + ": " + what : what);
  }
  return p;
}

Simulator::Simulator(const ScenarioParams& params) : p_(params) {
  world_ = buildWorld(p_.world, p_.seed, route_);
  if (p_.trajectory.start_offset_m > 0) route_ = routeStartingAt(route_, p_.trajectory.start_offset_m);
  trajectory_ = std::make_unique<Trajectory>(route_, world_.ground, p_.trajectory, &world_);
  // planned cars follow one another over the whole drive and a margin (carPose beyond it: last speed)
  world_.followTraffic(p_.world.followParams(std::max(p_.duration_s, trajectory_->duration_s()) + kTrafficMargin_s));
  lidar_ = std::make_unique<LidarSimulator>(world_, *trajectory_, p_.lidar, p_.seed);
}

Simulator::~Simulator() = default;

double Simulator::duration_s() const {
  return p_.duration_s > 0 ? p_.duration_s : trajectory_->duration_s();
}

uint32_t Simulator::packetTimestampUs(uint64_t k) const {
  const int64_t us = (p_.start_epoch_s % 3600) * 1000000 +
                     std::llround(static_cast<double>(k) * LidarSimulator::packetPeriod_s() * 1e6);
  return static_cast<uint32_t>(us % 3600000000LL);
}

double Simulator::packetCaptureTime(uint64_t k) const {
  return static_cast<double>(p_.start_epoch_s) + static_cast<double>(k + 1) * LidarSimulator::packetPeriod_s();
}

SimStats Simulator::runSweeps(const std::function<void(uint64_t, Scan&&)>& on_sweep,
                              std::vector<TrueReturn>* truth) {
  if (!p_.lidar.hdl64()) throw std::runtime_error("runSweeps: [lidar] model is not hdl64");
  const auto wall0 = std::chrono::steady_clock::now();
  SimStats st;
  st.sweeps = static_cast<uint64_t>(std::floor(duration_s() * p_.lidar.rotation_hz + 1e-9));
  Scan scan;
  for (uint64_t k = 0; k < st.sweeps; ++k) {
    if (stopRequested()) {
      st.sweeps = k;
      st.interrupted = true;
      break;
    }
    lidar_->simulateSweep(k, scan, truth);
    scan.stamp_s += static_cast<double>(p_.start_epoch_s);
    on_sweep(k, std::move(scan));
  }
  st.duration_s = static_cast<double>(st.sweeps) / p_.lidar.rotation_hz;
  st.distance_m = trajectory_->at(st.duration_s).s_m;
  st.lidar = lidar_->counters();
  st.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return st;
}

SimStats Simulator::run(PacketSink& sink, std::vector<TrueReturn>* truth) {
  if (p_.lidar.hdl64()) throw std::runtime_error("run: [lidar] model hdl64 has no packets (runSweeps)");
  const auto wall0 = std::chrono::steady_clock::now();
  const double T = duration_s(), P = LidarSimulator::packetPeriod_s();
  auto n = static_cast<uint64_t>(std::floor(T / P));
  std::array<velodyne::FiringSequence, velodyne::kVlp16SequencesPerPacket> seq{};
  SimStats st;
  double next_position_s = 0;  // simulation time of the next $GPRMC packet
  for (uint64_t k = 0; k < n; ++k) {
    if (stopRequested()) {  // the packets so far stay a valid capture; the outputs cover them
      n = k;
      st.interrupted = true;
      break;
    }
    lidar_->simulatePacket(k, seq, truth);
    const auto bytes = velodyne::encodeVlp16Packet(seq, packetTimestampUs(k));
    const double capture = packetCaptureTime(k);
    while (p_.position_packets && static_cast<double>(p_.start_epoch_s) + next_position_s <= capture) {
      const double epoch = static_cast<double>(p_.start_epoch_s) + next_position_s;
      const std::string nmea = gprmcSentence(p_, trajectory_->at(next_position_s), epoch);
      const uint32_t ts = static_cast<uint32_t>(
          ((p_.start_epoch_s % 3600) * 1000000 + std::llround(next_position_s * 1e6)) % 3600000000LL);
      const auto pos = velodyne::encodePositionPacket(ts, nmea.c_str());
      sink.packet(epoch, velodyne::kDefaultPositionPort, pos.data(), pos.size());
      ++st.position_packets;
      next_position_s += 1.0;
    }
    sink.packet(capture, velodyne::kDefaultDataPort, bytes.data(), bytes.size());
    ++st.data_packets;
  }
  st.duration_s = static_cast<double>(n) * P;
  st.sweeps = static_cast<uint64_t>(std::floor(st.duration_s * p_.lidar.rotation_hz));
  st.distance_m = trajectory_->at(st.duration_s).s_m;
  st.lidar = lidar_->counters();
  st.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return st;
}

std::string gprmcSentence(const ScenarioParams& p, const VehicleState& s, double epoch_s) {
  constexpr double kEarthRadius_m = 6378137.0;
  const double lat = p.origin_lat_deg + s.y / kEarthRadius_m * 180.0 / M_PI;
  const double lon = p.origin_lon_deg + s.x / (kEarthRadius_m * std::cos(p.origin_lat_deg * M_PI / 180.0)) * 180.0 / M_PI;
  const auto secs = static_cast<std::time_t>(std::floor(epoch_s));
  std::tm tm{};
  gmtime_r(&secs, &tm);
  const double sec = tm.tm_sec + (epoch_s - std::floor(epoch_s));
  const double alat = std::abs(lat), alon = std::abs(lon);
  const double course = std::fmod(450.0 - s.yaw * 180.0 / M_PI, 360.0);
  char body[160];
  std::snprintf(body, sizeof(body), "GPRMC,%02d%02d%05.2f,A,%02d%07.4f,%c,%03d%07.4f,%c,%.2f,%.1f,%02d%02d%02d,,,A",
                tm.tm_hour, tm.tm_min, sec, static_cast<int>(alat), (alat - std::floor(alat)) * 60.0,
                lat >= 0 ? 'N' : 'S', static_cast<int>(alon), (alon - std::floor(alon)) * 60.0,
                lon >= 0 ? 'E' : 'W', s.speed_mps * 3600.0 / 1852.0, course, tm.tm_mday, tm.tm_mon + 1,
                tm.tm_year % 100);
  uint8_t sum = 0;  // NMEA 0183: XOR of the characters between '$' and '*'
  for (const char* c = body; *c; ++c) sum ^= static_cast<uint8_t>(*c);
  char out[176];
  std::snprintf(out, sizeof(out), "$%s*%02X", body, sum);
  return out;
}

}  // namespace roadslam::sim
