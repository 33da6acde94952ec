// The sensor part of the report: every packet of a pcap, a rawlog or a grab folder's rawlog segments,
// grouped into streams (one per LiDAR source address and port, its position packets, GPS records).
#include <algorithm>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "internal.h"
#include "roadslam/sources/rawlog_source.h"
#include "roadslam/sources/recording.h"

namespace fs = std::filesystem;

namespace roadslam::recording_report {
namespace {

std::string ipText(uint32_t ip) {
  if (ip == 0) return "";
  return std::to_string(ip >> 24) + "." + std::to_string((ip >> 16) & 0xFF) + "." + std::to_string((ip >> 8) & 0xFF) +
         "." + std::to_string(ip & 0xFF) + ":";
}

/// One LiDAR's data packets: stamps, azimuth wraps (sweeps), packets missing from its own clock.
struct LidarAcc {
  explicit LidarAcc(velodyne::Model model) : forced(model) {}
  std::vector<double> stamps, wraps;
  velodyne::Model forced = velodyne::Model::Unknown;
  sources::GapCounter gaps{0, forced};
  int last_azimuth = -1;
  uint8_t product = 0, mode = 0;
  void feed(const velodyne::RawPacket& p) {
    stamps.push_back(p.stamp_s);
    gaps.feed(p.payload.data());
    const int az = p.payload[2] | (p.payload[3] << 8);  // first block azimuth [0.01 deg]
    if (last_azimuth >= 0 && az < last_azimuth - 18000) wraps.push_back(p.stamp_s);  // a turn completed
    last_azimuth = az;
    product = forced != velodyne::Model::Unknown ? static_cast<uint8_t>(forced) : p.payload[1205];
    mode = p.payload[1204];
  }
};

/// Complete turns: wrap-to-wrap intervals up to 1.5 x their median (a longer one spans lost packets);
/// the rotation rate from their mean length.
void sweepRate(const std::vector<double>& wraps, StreamStats& s) {
  std::vector<double> dt;
  for (size_t i = 1; i < wraps.size(); ++i) dt.push_back(wraps[i] - wraps[i - 1]);
  if (dt.empty()) return;
  std::vector<double> sorted = dt;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  double sum = 0;
  for (double d : dt)
    if (d <= 1.5 * median) sum += d, ++s.sweeps;
  if (sum > 0) s.sweep_rate_hz = static_cast<double>(s.sweeps) / sum;
}

std::string modelName(uint8_t product) {
  switch (static_cast<velodyne::Model>(product)) {
    case velodyne::Model::VLP16: return "vlp16";
    case velodyne::Model::HDL32: return "hdl32";
    default: return "unknown (0x" + std::to_string(product) + ")";
  }
}

}  // namespace

std::vector<std::string> recordingFiles(const std::string& path) {
  if (!fs::is_directory(path)) return {path};
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(path)) {
    const std::string n = e.path().filename().string();
    if (e.is_regular_file() && n.find(".rawlog") != std::string::npos && n.find(".ini") == std::string::npos)
      files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());  // grab_000, grab_001, ...: recording order
  if (files.empty()) throw std::runtime_error(path + ": a folder without rawlog segments (grab_*.rawlog)");
  return files;
}

std::vector<PendingStream> readSensors(RecordingReport& r, const std::string& lidar_model) {
  sources::PortConfig ports;
  if (lidar_model == "vlp16") ports.model = velodyne::Model::VLP16;
  else if (lidar_model == "hdl32") ports.model = velodyne::Model::HDL32;
  else if (!lidar_model.empty()) throw std::runtime_error("unknown LiDAR model '" + lidar_model + "' (vlp16 or hdl32)");
  std::map<std::string, LidarAcc> lidars;
  std::map<std::string, std::vector<double>> other;    // position packets, GPS records
  std::map<std::string, std::vector<double>> vehicle;  // other rawlog records by label (CAN observations)
  uint64_t malformed = 0;
  for (const std::string& file : r.files) {
    auto src = sources::openRecording(file, ports);
    auto* rawlog = dynamic_cast<sources::RawlogPacketSource*>(src.get());
    r.format = rawlog ? "rawlog" : "pcap";
    if (rawlog) rawlog->keepOtherRecords(true);
    const auto takeOthers = [&] {
      if (!rawlog) return;
      for (const auto& o : rawlog->takeOtherRecords()) {
        const std::string cls = o.class_name.substr(o.class_name.rfind(':') == std::string::npos ? 0 : o.class_name.rfind(':') + 1);
        vehicle[o.label.empty() ? cls : o.label + " (" + cls + ")"].push_back(o.stamp_s);
      }
    };
    while (auto pkt = src->next()) {
      // a rawlog keeps no address: its LiDARs are told apart by the scans' sensorLabel
      const std::string where = rawlog && !rawlog->scanLabel().empty() && pkt->payload.size() == velodyne::kDataPacketSize
                                    ? rawlog->scanLabel()
                                    : ipText(pkt->src_ip) + std::to_string(pkt->dst_port);
      if (pkt->payload.size() == velodyne::kDataPacketSize) {
        auto it = lidars.find("velodyne " + where);
        if (it == lidars.end()) it = lidars.emplace("velodyne " + where, LidarAcc(ports.model)).first;
        it->second.feed(*pkt);
      } else {
        other["position packets " + where].push_back(pkt->stamp_s);
      }
      for (const auto& fix : src->takeDecodedFixes()) other["gps (rawlog)"].push_back(fix.stamp_s);
      takeOthers();
    }
    for (const auto& fix : src->takeDecodedFixes()) other["gps (rawlog)"].push_back(fix.stamp_s);
    takeOthers();
    malformed += src->stats().malformed_packets;
    if (rawlog) r.sensor_records += rawlog->otherRecords();
    if (!src->errorMessage().empty()) {
      if (lidars.empty() && other.empty() && vehicle.empty()) throw std::runtime_error(src->errorMessage());
      r.damage = src->errorMessage();
      if (rawlog)  // the place as a record count too (the byte is in the uncompressed stream)
        r.damage += "; " + std::to_string(rawlog->scansRead() + rawlog->otherRecords() + src->stats().position_packets) +
                    " records read before it";
      break;  // the segments after a damaged one are not read: the report covers the data before it
    }
  }
  if (lidars.empty() && other.empty() && vehicle.empty())
    throw std::runtime_error(r.recording + ": no Velodyne, GPS or other sensor data in it");
  std::vector<PendingStream> out;
  for (auto& [label, acc] : lidars) {
    PendingStream ps;
    const bool dual = acc.mode == static_cast<uint8_t>(velodyne::ReturnMode::Dual);
    const auto model = static_cast<velodyne::Model>(acc.product);
    if (model != velodyne::Model::Unknown) ps.nominal_period_s = sources::GapCounter::packetPeriod_s(model, dual);
    ps.info.label = label;
    ps.info.kind = "lidar";
    ps.info.model = modelName(acc.product);
    ps.info.drops = acc.gaps.missing();
    ps.info.malformed = malformed;
    sweepRate(acc.wraps, ps.info);
    ps.stamps = std::move(acc.stamps);
    out.push_back(std::move(ps));
  }
  for (auto& [label, t] : other) {
    PendingStream ps;
    ps.info.label = label;
    ps.info.kind = "gps";
    ps.stamps = std::move(t);
    out.push_back(std::move(ps));
  }
  for (auto& [label, t] : vehicle) {
    PendingStream ps;
    ps.info.label = label;
    ps.info.kind = "rawlog";
    ps.stamps = std::move(t);
    out.push_back(std::move(ps));
  }
  return out;
}

}  // namespace roadslam::recording_report
