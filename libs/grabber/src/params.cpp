#include "roadslam/grabber/params.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::grabber {
namespace {

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    item.erase(0, item.find_first_not_of(" \t"));
    item.erase(item.find_last_not_of(" \t") + 1);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

void rejectUnknown(const mrpt::config::CConfigFileBase& cfg, const std::string& sec,
                   const std::vector<std::string>& known) {
  rejectUnknownKeys(cfg, sec, known);
}

const NameTable<CanParams::Source>& canSourceNames() {
  using S = CanParams::Source;
  static const NameTable<S> t{{S::None, "none"}, {S::SocketCan, "socketcan"}, {S::Candump, "candump"}};
  return t;
}

const NameTable<GnssParams::Source>& gnssSourceNames() {
  using S = GnssParams::Source;
  static const NameTable<S> t{{S::None, "none"}, {S::Serial, "serial"}, {S::Gpsd, "gpsd"}, {S::NmeaLog, "nmea_log"}};
  return t;
}

/// The keys of a section read by several tables.
std::vector<std::string> joined(std::vector<std::vector<std::string>> parts) {
  std::vector<std::string> out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

}  // namespace

void SensorParams::fields(ParamTable& t) {
  t.scaled("silent_after_ms", silent_after_s, unit::kMs);
  t.flag("lock_first_sender", lock_first_sender);
}

void SensorParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& sec) {
  rejectUnknown(cfg, sec, joined({fieldKeys<sources::UdpReceiver::Params>(), fieldKeys<rawlog::RawlogWriter::Params>(),
                                  fieldKeys<SensorParams>()}));
  section = sec;
  udp.loadFromConfigFile(cfg, sec);
  scan.sensor_label = sec;
  scan.gps_label = sec + "_GPS";
  scan.loadFromConfigFile(cfg, sec);
  // One "model" key serves both: the receiver's gap counter (auto|vlp16|hdl32) and MRPT's
  // default calibration name (VLP16|HDL32).
  scan.model = udp.ports.model == velodyne::Model::HDL32 ? "HDL32" : "VLP16";
  loadFields(*this, cfg, sec);
  if (silent_after_s <= 0) throw std::runtime_error("[" + sec + "] silent_after_ms: must be > 0");
}

void SensorParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const {
  udp.saveToConfigFile(cfg, section);
  scan.saveToConfigFile(cfg, section);
  saveFields(*this, cfg, section);
}

void CanParams::fields(ParamTable& t) {
  t.choice("source", source, canSourceNames());
  socketcan.fields(t);
  t.text("candump_file", candump_file);
  t.flag("candump_realtime", candump_realtime);
  t.flag("restamp", restamp);
  t.text("vehicle_ini", vehicle_ini);
  t.text("data_root", data_root);
  t.scaled("silent_after_ms", silent_after_s, unit::kMs);
}

void CanParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& sec) {
  rejectUnknown(cfg, sec, fieldKeys<CanParams>());
  loadFields(*this, cfg, sec);
  if (silent_after_s <= 0) throw std::runtime_error("[" + sec + "] silent_after_ms: must be > 0");
  if (source == Source::Candump && candump_file.empty())
    throw std::runtime_error("[" + sec + "] candump_file: required when source = candump");
}

void CanParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& sec) const {
  saveFields(*this, cfg, sec);
}

void GnssParams::fields(ParamTable& t) {
  t.choice("source", source, gnssSourceNames());
  t.text("device", device);
  t.num("baud", baud);
  t.text("gpsd_host", gpsd_host);
  t.num("gpsd_port", gpsd_port);
  t.text("gpsd_device", gpsd_device);
  t.text("nmea_file", nmea_file);
  t.num("replay_speed", replay_speed);
  t.flag("restamp", restamp);
  t.text("label", label);
  t.scaled("epoch_idle_ms", epoch_idle_s, unit::kMs);
  t.scaled("max_gap_ms", max_gap_s, unit::kMs);
  t.scaled("silent_after_ms", silent_after_s, unit::kMs);
}

void GnssParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& sec) {
  rejectUnknown(cfg, sec, fieldKeys<GnssParams>());
  loadFields(*this, cfg, sec);
  if (silent_after_s <= 0) throw std::runtime_error("[" + sec + "] silent_after_ms: must be > 0");
  if (epoch_idle_s <= 0) throw std::runtime_error("[" + sec + "] epoch_idle_ms: must be > 0");
  if (max_gap_s <= 0) throw std::runtime_error("[" + sec + "] max_gap_ms: must be > 0");
  if (replay_speed < 0) throw std::runtime_error("[" + sec + "] replay_speed: must be >= 0");
  if (gpsd_port < 1 || gpsd_port > 65535) throw std::runtime_error("[" + sec + "] gpsd_port: must be 1..65535");
  if (source == Source::NmeaLog && nmea_file.empty())
    throw std::runtime_error("[" + sec + "] nmea_file: required when source = nmea_log");
  if (source == Source::Serial && device.empty())
    throw std::runtime_error("[" + sec + "] device: required when source = serial");
}

void GnssParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& sec) const {
  saveFields(*this, cfg, sec);
}

void WriterParams::fields(ParamTable& t) {
  t.num("queue_capacity", queue_capacity);
  t.num("can_queue_capacity", can_queue_capacity);
  t.scaled("rotate_size_mb", rotate_size_bytes, unit::kMb);
  t.num("rotate_period_s", rotate_period_s);
  t.scaled("flush_period_ms", flush_period_s, unit::kMs);
  t.scaled("reorder_window_ms", reorder_window_s, unit::kMs);
  t.num("compression_level", compression_level);
  t.flag("pcap_sidecar", pcap_sidecar);
  t.flag("candump_sidecar", candump_sidecar);
  t.flag("nmea_sidecar", nmea_sidecar);
  t.scaled("status_period_ms", status_period_s, unit::kMs);
  t.text("file_prefix", file_prefix);
}

void WriterParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  if (queue_capacity < 1 || can_queue_capacity < 1)
    throw std::runtime_error("[" + s + "] queue_capacity / can_queue_capacity: must be >= 1");
  if (flush_period_s <= 0 || status_period_s <= 0)
    throw std::runtime_error("[" + s + "] flush_period_ms / status_period_ms: must be > 0");
  if (compression_level < 0 || compression_level > 9)
    throw std::runtime_error("[" + s + "] compression_level: must be 0..9");
  if (reorder_window_s < 0) throw std::runtime_error("[" + s + "] reorder_window_ms: must be >= 0");
}

void WriterParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

void GrabParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg) {
  rejectUnknown(cfg, "grab", joined({{"sensors", "can", "gnss"}, fieldKeys<WriterParams>()}));
  writer.loadFromConfigFile(cfg, "grab");
  const auto names = splitList(readString(cfg, "grab", "sensors", ""));
  if (names.empty()) throw std::runtime_error("[grab] sensors: at least one sensor section is required");
  sensors.clear();
  for (const auto& n : names) {
    SensorParams sp;
    sp.loadFromConfigFile(cfg, n);
    for (const auto& other : sensors)
      if (other.udp.ports.data_port == sp.udp.ports.data_port && sp.udp.ports.data_port != 0 &&
          other.udp.bind_address == sp.udp.bind_address)
        throw std::runtime_error("[" + n + "] data_port: " + std::to_string(sp.udp.ports.data_port) +
                                 " already used by [" + other.section + "]");
    sensors.push_back(sp);
  }
  const std::string can_sec = readString(cfg, "grab", "can", "");
  can = CanParams{};
  if (!can_sec.empty()) can.loadFromConfigFile(cfg, can_sec);
  const std::string gnss_sec = readString(cfg, "grab", "gnss", "");
  gnss = GnssParams{};
  if (!gnss_sec.empty()) gnss.loadFromConfigFile(cfg, gnss_sec);
}

void GrabParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const {
  std::string names;
  for (const auto& s : sensors) names += (names.empty() ? "" : ",") + s.section;
  cfg.write("grab", "sensors", names);
  cfg.write("grab", "can", std::string(can.source == CanParams::Source::None ? "" : "can"));
  cfg.write("grab", "gnss", std::string(gnss.source == GnssParams::Source::None ? "" : "gnss"));
  writer.saveToConfigFile(cfg, "grab");
  for (const auto& s : sensors) s.saveToConfigFile(cfg);
  if (can.source != CanParams::Source::None) can.saveToConfigFile(cfg, "can");
  if (gnss.source != GnssParams::Source::None) gnss.saveToConfigFile(cfg, "gnss");
}

GrabParams GrabParams::fromFile(const std::string& path) {
  auto cfg = loadIniFile(path);
  GrabParams p;
  try {
    p.loadFromConfigFile(*cfg);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  // Paths in the ini are relative to the ini file, so a session runs from any folder.
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  auto resolve = [&](std::string& f) {
    if (!f.empty() && std::filesystem::path(f).is_relative()) f = (base / f).lexically_normal().string();
  };
  for (auto& s : p.sensors) resolve(s.scan.calibration_file);
  resolve(p.can.candump_file);
  resolve(p.can.vehicle_ini);
  resolve(p.gnss.nmea_file);
  return p;
}

}  // namespace roadslam::grabber
