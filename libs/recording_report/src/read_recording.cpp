// The sensor part of the report: every packet of a pcap, a rawlog or a grab folder's rawlog segments,
// grouped into streams (one per LiDAR source address and port, its position packets, GPS records).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "internal.h"
#include "roadslam/rawlog/rawlog_session.h"
#include "roadslam/velodyne/model_choice.h"
#include "roadslam/sources/gps_fix.h"
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
  velodyne::LayoutDetector layout;  // the model by the packets (velodyne/model_choice.h)
  int last_azimuth = -1;
  uint8_t product = 0, mode = 0;
  void feed(const velodyne::RawPacket& p) {
    stamps.push_back(p.stamp_s);
    gaps.feed(p.payload.data());
    layout.add(p.payload.data(), p.payload.size());
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
    default: {
      char b[32];
      std::snprintf(b, sizeof b, "unknown (0x%02X)", product);
      return b;
    }
  }
}

}  // namespace

std::vector<std::string> recordingFiles(const std::string& path) {
  if (!fs::is_directory(path)) return {path};
  // the segments as every reader takes them: PREFIX_NNN.rawlog, in order; not their .idx or .ini
  std::vector<std::string> files = rawlog::RawlogSession::segmentsOf(path);
  if (files.empty()) throw std::runtime_error(path + ": a folder without rawlog segments (grab_*.rawlog)");
  return files;
}

namespace {

/// Every stream of a recording's files, accumulated packet by packet.
struct SensorStreams {
  sources::PortConfig ports;
  std::map<std::string, LidarAcc> lidars;
  std::map<std::string, std::vector<double>> gps;    // position packets, GPS records
  std::map<std::string, std::vector<double>> other;  // other rawlog records by label and class
  uint64_t malformed = 0;
  std::vector<gnss::GnssFix> fixes;  // valid RMC fixes

  bool empty() const { return lidars.empty() && gps.empty() && other.empty(); }

  void add(const velodyne::RawPacket& pkt, const sources::RawlogPacketSource* rawlog) {
    const bool data = pkt.payload.size() == velodyne::kDataPacketSize;
    // a rawlog keeps no address: its LiDARs are told apart by the scans' sensorLabel
    const std::string where = rawlog && data && !rawlog->scanLabel().empty()
                                  ? rawlog->scanLabel()
                                  : ipText(pkt.src_ip) + std::to_string(pkt.dst_port);
    if (!data) {
      gps["position packets " + where].push_back(pkt.stamp_s);
      if (auto f = sources::decodeGpsFix(pkt); f && f->valid()) fixes.push_back(*f);
      return;
    }
    auto it = lidars.find("velodyne " + where);
    if (it == lidars.end()) it = lidars.emplace("velodyne " + where, LidarAcc(ports.model)).first;
    it->second.feed(pkt);
  }

  /// GPS fixes and other records the source decoded since the last call.
  void takeDecoded(sources::PacketSource& src, sources::RawlogPacketSource* rawlog) {
    for (const auto& fix : src.takeDecodedFixes()) {
      gps["gps (rawlog)"].push_back(fix.t_receive_s);
      if (fix.valid()) fixes.push_back(fix);
    }
    if (!rawlog) return;
    for (const auto& o : rawlog->takeOtherRecords()) {
      const auto colon = o.class_name.rfind(':');
      const std::string cls = colon == std::string::npos ? o.class_name : o.class_name.substr(colon + 1);
      other[o.label.empty() ? cls : o.label + " (" + cls + ")"].push_back(o.stamp_s);
    }
  }

  /// Reads one file; returns false when it is damaged (RecordingReport::damage set).
  bool read(const std::string& file, RecordingReport& r) {
    auto src = sources::openRecording(file, ports);
    auto* rawlog = dynamic_cast<sources::RawlogPacketSource*>(src.get());
    r.format = rawlog ? "rawlog" : "pcap";
    if (rawlog) rawlog->keepOtherRecords(true);
    while (auto pkt = src->next()) {
      add(*pkt, rawlog);
      takeDecoded(*src, rawlog);
    }
    takeDecoded(*src, rawlog);
    malformed += src->stats().malformed_packets;
    if (rawlog) r.sensor_records += rawlog->otherRecords();
    if (src->errorMessage().empty()) return true;
    if (empty()) throw std::runtime_error(src->errorMessage());
    r.damage = src->errorMessage();
    if (rawlog)  // the place as a record count too (the byte is in the uncompressed stream)
      r.damage += "; " + std::to_string(rawlog->scansRead() + rawlog->otherRecords() + src->stats().position_packets) +
                  " records read before it";
    return false;
  }

  /// The streams; a LiDAR's model as every program decodes it (velodyne::chooseModel), its
  /// disagreement with the product byte or the set model into \p warnings.
  std::vector<PendingStream> streams(std::vector<std::string>& warnings) {
    std::vector<PendingStream> out;
    for (auto& [label, acc] : lidars) {
      PendingStream ps;
      const bool dual = acc.mode == static_cast<uint8_t>(velodyne::ReturnMode::Dual);
      const velodyne::ModelChoice c = velodyne::chooseModel(acc.forced, acc.layout.verdict(), "--lidar-model");
      if (!c.warning.empty()) warnings.push_back(label + ": " + c.warning);
      if (c.model != velodyne::Model::Unknown) ps.nominal_period_s = sources::GapCounter::packetPeriod_s(c.model, dual);
      ps.info.label = label;
      ps.info.kind = "lidar";
      ps.info.model = c.model != velodyne::Model::Unknown ? modelName(static_cast<uint8_t>(c.model)) : modelName(acc.product);
      ps.info.model_source = velodyne::toString(c.source);
      ps.info.drops = acc.gaps.missing();
      ps.info.malformed = malformed;
      sweepRate(acc.wraps, ps.info);
      ps.stamps = std::move(acc.stamps);
      out.push_back(std::move(ps));
    }
    for (auto* m : {&gps, &other}) {
      for (auto& [label, t] : *m) {
        PendingStream ps;
        ps.info.label = label;
        ps.info.kind = m == &gps ? "gps" : "rawlog";
        ps.stamps = std::move(t);
        out.push_back(std::move(ps));
      }
    }
    return out;
  }
};

}  // namespace

/// The fixes in a local east-north plane about the first (equirectangular; WGS84 equatorial radius).
void gnssPath(std::vector<gnss::GnssFix> fixes, RecordingReport& r) {
  constexpr double kEarthRadius_m = 6378137.0, kDeg = M_PI / 180.0;
  std::stable_sort(fixes.begin(), fixes.end(), [](const auto& a, const auto& b) { return a.t_receive_s < b.t_receive_s; });
  if (fixes.empty()) return;
  const double lat0 = fixes[0].position.lat_deg, lon0 = fixes[0].position.lon_deg;
  for (const auto& f : fixes) {
    const double x = (f.position.lon_deg - lon0) * kDeg * kEarthRadius_m * std::cos(lat0 * kDeg);
    const double y = (f.position.lat_deg - lat0) * kDeg * kEarthRadius_m;
    if (!r.gnss_x_m.empty()) r.gnss_length_m += std::hypot(x - r.gnss_x_m.back(), y - r.gnss_y_m.back());
    r.gnss_t_s.push_back(f.t_receive_s);
    r.gnss_x_m.push_back(x);
    r.gnss_y_m.push_back(y);
  }
  r.gnss_fixes = fixes.size();
}

std::vector<PendingStream> readSensors(RecordingReport& r, const std::string& lidar_model) {
  SensorStreams s;
  if (lidar_model == "vlp16") s.ports.model = velodyne::Model::VLP16;
  else if (lidar_model == "hdl32") s.ports.model = velodyne::Model::HDL32;
  else if (!lidar_model.empty()) throw std::runtime_error("unknown LiDAR model '" + lidar_model + "' (vlp16 or hdl32)");
  for (const std::string& file : r.files) {
    if (!s.read(file, r)) break;  // the segments after a damaged one are not read: the report covers the data before it
  }
  if (s.empty()) throw std::runtime_error(r.recording + ": no Velodyne, GPS or other sensor data in it");
  gnssPath(std::move(s.fixes), r);
  return s.streams(r.warnings);
}

}  // namespace roadslam::recording_report
