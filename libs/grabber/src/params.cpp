#include "roadslam/grabber/params.h"

#include <mrpt/config/CConfigFileBase.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "roadslam/common/config.h"

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

const std::vector<std::string> kSensorKeys = {
    "data_port", "position_port", "model", "bind_address", "source_filter", "rcvbuf_bytes",
    "batch_size", "poll_timeout_ms", "packet_period_us", "sensor_label", "gps_label",
    "calibration_file", "min_range_m", "max_range_m", "x_m", "y_m", "z_m", "yaw_deg", "pitch_deg",
    "roll_deg", "silent_after_ms", "lock_first_sender"};
const std::vector<std::string> kCanKeys = {
    "source", "interface", "filters", "error_frames", "fd", "receive_buffer_bytes",
    "reopen_interval_ms", "candump_file", "candump_realtime", "restamp", "vehicle_ini", "data_root",
    "silent_after_ms"};
const std::vector<std::string> kGrabKeys = {
    "sensors", "can", "queue_capacity", "can_queue_capacity", "rotate_size_mb", "rotate_period_s",
    "flush_period_ms", "reorder_window_ms", "compression_level", "pcap_sidecar", "candump_sidecar",
    "status_period_ms", "file_prefix"};

}  // namespace

void SensorParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& sec) {
  rejectUnknown(cfg, sec, kSensorKeys);
  section = sec;
  udp.loadFromConfigFile(cfg, sec);
  scan.sensor_label = sec;
  scan.gps_label = sec + "_GPS";
  scan.loadFromConfigFile(cfg, sec);
  // One "model" key serves both: the receiver's gap counter (auto|vlp16|hdl32) and MRPT's
  // default calibration name (VLP16|HDL32).
  scan.model = udp.ports.model == velodyne::Model::HDL32 ? "HDL32" : "VLP16";
  silent_after_s = readDouble(cfg, sec, "silent_after_ms", silent_after_s * 1e3) * 1e-3;
  if (silent_after_s <= 0) throw std::runtime_error("[" + sec + "] silent_after_ms: must be > 0");
  lock_first_sender = readBool(cfg, sec, "lock_first_sender", lock_first_sender);
}

void SensorParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const {
  udp.saveToConfigFile(cfg, section);
  scan.saveToConfigFile(cfg, section);
  cfg.write(section, "silent_after_ms", silent_after_s * 1e3);
  cfg.write(section, "lock_first_sender", lock_first_sender);
}

void CanParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& sec) {
  rejectUnknown(cfg, sec, kCanKeys);
  const std::string s = readString(cfg, sec, "source", "none");
  if (s == "none") source = Source::None;
  else if (s == "socketcan") source = Source::SocketCan;
  else if (s == "candump") source = Source::Candump;
  else throw std::runtime_error("[" + sec + "] source: expected none, socketcan or candump, got '" + s + "'");
  socketcan.loadFromConfigFile(cfg, sec);
  candump_file = readString(cfg, sec, "candump_file", candump_file);
  candump_realtime = readBool(cfg, sec, "candump_realtime", candump_realtime);
  restamp = readBool(cfg, sec, "restamp", restamp);
  vehicle_ini = readString(cfg, sec, "vehicle_ini", vehicle_ini);
  data_root = readString(cfg, sec, "data_root", data_root);
  silent_after_s = readDouble(cfg, sec, "silent_after_ms", silent_after_s * 1e3) * 1e-3;
  if (silent_after_s <= 0) throw std::runtime_error("[" + sec + "] silent_after_ms: must be > 0");
  if (source == Source::Candump && candump_file.empty())
    throw std::runtime_error("[" + sec + "] candump_file: required when source = candump");
}

void CanParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& sec) const {
  const char* names[] = {"none", "socketcan", "candump"};
  cfg.write(sec, "source", std::string(names[static_cast<int>(source)]));
  socketcan.saveToConfigFile(cfg, sec);
  cfg.write(sec, "candump_file", candump_file);
  cfg.write(sec, "candump_realtime", candump_realtime);
  cfg.write(sec, "restamp", restamp);
  cfg.write(sec, "vehicle_ini", vehicle_ini);
  cfg.write(sec, "data_root", data_root);
  cfg.write(sec, "silent_after_ms", silent_after_s * 1e3);
}

void WriterParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  queue_capacity = std::size_t(readInt(cfg, s, "queue_capacity", int(queue_capacity)));
  can_queue_capacity = std::size_t(readInt(cfg, s, "can_queue_capacity", int(can_queue_capacity)));
  rotate_size_bytes = readDouble(cfg, s, "rotate_size_mb", rotate_size_bytes / 1e6) * 1e6;
  rotate_period_s = readDouble(cfg, s, "rotate_period_s", rotate_period_s);
  flush_period_s = readDouble(cfg, s, "flush_period_ms", flush_period_s * 1e3) * 1e-3;
  reorder_window_s = readDouble(cfg, s, "reorder_window_ms", reorder_window_s * 1e3) * 1e-3;
  compression_level = readInt(cfg, s, "compression_level", compression_level);
  pcap_sidecar = readBool(cfg, s, "pcap_sidecar", pcap_sidecar);
  candump_sidecar = readBool(cfg, s, "candump_sidecar", candump_sidecar);
  status_period_s = readDouble(cfg, s, "status_period_ms", status_period_s * 1e3) * 1e-3;
  file_prefix = readString(cfg, s, "file_prefix", file_prefix);
  if (queue_capacity < 1 || can_queue_capacity < 1)
    throw std::runtime_error("[" + s + "] queue_capacity / can_queue_capacity: must be >= 1");
  if (flush_period_s <= 0 || status_period_s <= 0)
    throw std::runtime_error("[" + s + "] flush_period_ms / status_period_ms: must be > 0");
  if (compression_level < 0 || compression_level > 9)
    throw std::runtime_error("[" + s + "] compression_level: must be 0..9");
  if (reorder_window_s < 0) throw std::runtime_error("[" + s + "] reorder_window_ms: must be >= 0");
}

void WriterParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  cfg.write(s, "queue_capacity", int(queue_capacity));
  cfg.write(s, "can_queue_capacity", int(can_queue_capacity));
  cfg.write(s, "rotate_size_mb", rotate_size_bytes / 1e6);
  cfg.write(s, "rotate_period_s", rotate_period_s);
  cfg.write(s, "flush_period_ms", flush_period_s * 1e3);
  cfg.write(s, "reorder_window_ms", reorder_window_s * 1e3);
  cfg.write(s, "compression_level", compression_level);
  cfg.write(s, "pcap_sidecar", pcap_sidecar);
  cfg.write(s, "candump_sidecar", candump_sidecar);
  cfg.write(s, "status_period_ms", status_period_s * 1e3);
  cfg.write(s, "file_prefix", file_prefix);
}

void GrabParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg) {
  rejectUnknown(cfg, "grab", kGrabKeys);
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
}

void GrabParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const {
  std::string names;
  for (const auto& s : sensors) names += (names.empty() ? "" : ",") + s.section;
  cfg.write("grab", "sensors", names);
  cfg.write("grab", "can", std::string(can.source == CanParams::Source::None ? "" : "can"));
  writer.saveToConfigFile(cfg, "grab");
  for (const auto& s : sensors) s.saveToConfigFile(cfg);
  if (can.source != CanParams::Source::None) can.saveToConfigFile(cfg, "can");
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
  return p;
}

}  // namespace roadslam::grabber
