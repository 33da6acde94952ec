#include "roadslam/sources/recording.h"

#include <filesystem>
#include <mrpt/config/CConfigFileMemory.h>
#include <nlohmann/json.hpp>
#include <fmt/core.h>

#include <fstream>
#include <stdexcept>
#include <sys/stat.h>

#include "roadslam/common/atomic_file.h"
#include "roadslam/sources/pcap_source.h"
#include "roadslam/sources/rawlog_source.h"
#include "roadslam/sources/sweep_source.h"

namespace roadslam::sources {
namespace {

bool isPcapMagic(uint32_t m) {
  // pcap-savefile(5): us / ns magic in either byte order; pcapng section header block type.
  return m == 0xA1B2C3D4u || m == 0xD4C3B2A1u || m == 0xA1B23C4Du || m == 0x4D3CB2A1u ||
         m == 0x0A0D0D0Au;
}

void requireNonEmptyFile(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) throw std::runtime_error(path + ": no such file");
  if (!S_ISREG(st.st_mode)) throw std::runtime_error(path + ": not a regular file");
  if (st.st_size == 0) throw std::runtime_error(path + ": empty file");
}

}  // namespace

std::unique_ptr<PacketSource> openRecording(const std::string& path, const PortConfig& ports) {
  requireNonEmptyFile(path);
  uint32_t magic = 0;
  std::ifstream(path, std::ios::binary).read(reinterpret_cast<char*>(&magic), sizeof magic);
  try {
    if (isPcapMagic(magic)) return std::make_unique<PcapPacketSource>(path, ports);
    return std::make_unique<RawlogPacketSource>(path, ports);
  } catch (const std::exception& e) {
    const std::string what = e.what();
    throw std::runtime_error(what.find(path) != std::string::npos ? what : path + ": " + what);
  }
}

RecordingSummary summarizeRecording(const std::string& path, const velodyne::DecoderParams& params,
                                    const std::string& force_setting) {
  PortConfig ports;
  ports.model = params.model;
  SweepSource sweeps(openRecording(path, ports), params, force_setting);
  RecordingSummary s;
  s.path = path;
  s.format = dynamic_cast<const PcapPacketSource*>(&sweeps.packets()) ? "pcap" : "rawlog";
  double first_data_s = 0, last_data_s = 0;
  sweeps.setPacketObserver([&](const velodyne::RawPacket& p, std::size_t) {
    if (p.payload.size() != velodyne::kDataPacketSize) return;
    if (s.model.empty()) {
      s.model = velodyne::modelName(sweeps.decoder().modelOf(p.payload.data(), p.payload.size()));
      first_data_s = p.stamp_s;
    }
    last_data_s = p.stamp_s;
  });
  while (auto scan = sweeps.next()) {
    (scan->partial ? s.partial_sweeps : s.sweeps)++;
    sweeps.takeGpsFixes();
  }
  sweeps.takeGpsFixes();
  const std::string err = sweeps.packets().errorMessage();
  const SourceStats& ps = sweeps.packets().stats();
  if (ps.data_packets == 0) throw std::runtime_error(err.empty() ? path + ": no Velodyne data packets" : err);
  s.damage = damageWarning(sweeps);
  const SweepSourceStats& ss = sweeps.sweepStats();
  s.packets = ps.data_packets;
  s.position_packets = ps.position_packets;
  s.points = ss.points;
  s.gps_fixes = ss.gps_fixes;
  s.malformed_packets = ps.malformed_packets + ss.undecodable_packets;
  s.skipped_packets = ps.skipped_packets;
  s.missing_packets = ps.missing_packets;
  s.duration_s = last_data_s - first_data_s;
  s.sweeps_per_s = ss.sweepRate_hz();
  s.packets_per_s = s.duration_s > 0 ? double(s.packets - 1) / s.duration_s : 0.0;
  if (const auto m = sweeps.lidarModel()) {
    s.lidar_model = m->model;
    s.lidar_model_source = m->source;
    s.lidar_layout = m->layout;
  }
  s.warnings = sweeps.warnings();
  return s;
}

std::string toJson(const RecordingSummary& s) {
  const nlohmann::json j = {
      {"path", s.path},           {"format", s.format},
      {"model", s.model},         {"lidar_model", s.lidar_model},
      {"lidar_model_source", s.lidar_model_source}, {"lidar_layout", s.lidar_layout},
      {"warnings", s.warnings},   {"sweeps", s.sweeps},
      {"partial_sweeps", s.partial_sweeps},
      {"packets", s.packets},     {"position_packets", s.position_packets},
      {"points", s.points},       {"gps_fixes", s.gps_fixes},
      {"malformed_packets", s.malformed_packets},
      {"skipped_packets", s.skipped_packets},
      {"missing_packets", s.missing_packets},
      {"duration_s", s.duration_s}, {"sweeps_per_s", s.sweeps_per_s},
      {"packets_per_s", s.packets_per_s}, {"damage", s.damage}};
  return j.dump(2);
}

std::string toText(const RecordingSummary& s) {
  std::string t = fmt::format("{} ({}, {})\n", s.path, s.format, s.model);
  t += fmt::format("  lidar model       {} (by {}; {})\n", s.lidar_model, s.lidar_model_source, s.lidar_layout);
  t += fmt::format("  sweeps            {} complete + {} partial\n", s.sweeps, s.partial_sweeps);
  t += fmt::format("  data packets      {}\n", s.packets);
  t += fmt::format("  points            {}\n", s.points);
  t += fmt::format("  duration          {:.3f} s\n", s.duration_s);
  t += fmt::format("  rate              {:.2f} sweeps/s, {:.1f} packets/s\n", s.sweeps_per_s,
                   s.packets_per_s);
  t += fmt::format("  position packets  {} ({} GPS fixes)\n", s.position_packets, s.gps_fixes);
  t += fmt::format("  malformed packets {}\n", s.malformed_packets);
  t += fmt::format("  skipped packets   {}\n", s.skipped_packets);
  t += fmt::format("  missing packets   {}\n", s.missing_packets);
  if (!s.damage.empty()) t += "  damaged           yes: the figures cover the data before the damage\n";
  return t;
}

ConvertSummary convertToRawlog(const std::string& in, const std::string& out,
                               const velodyne::DecoderParams& params,
                               rawlog::RawlogWriter::Params writer_params, const std::string& force_setting) {
  std::error_code ec;
  if (std::filesystem::equivalent(in, out, ec)) {
    throw std::runtime_error("'" + out + "' is the input: the conversion would overwrite what it reads");
  }
  PortConfig ports;
  ports.model = params.model;
  SweepSource sweeps(openRecording(in, ports), params, force_setting);
  if (writer_params.calibration_file.empty()) writer_params.calibration_file = params.calibration_file;
  bool model_set = params.model != velodyne::Model::Unknown;
  if (model_set) writer_params.model = params.model == velodyne::Model::HDL32 ? "HDL32" : "VLP16";
  std::unique_ptr<rawlog::RawlogWriter> writer;  // opened at the first data packet, once the model is known
  std::vector<velodyne::RawPacket> pending, pending_gps;
  ConvertSummary sum;
  // Observations go out in time order: a sweep is stamped with its first packet, so the position
  // packets that arrived during it are written after it.
  auto flush = [&] {
    if (!pending.empty()) {
      writer->writeSweep(pending);
      ++sum.observations;
    }
    for (const auto& g : pending_gps) writer->writePosition(g);
    pending.clear();
    pending_gps.clear();
  };
  sweeps.setPacketObserver([&](const velodyne::RawPacket& p, std::size_t closed) {
    if (!writer) {
      if (!model_set && p.payload.size() == velodyne::kDataPacketSize)
        writer_params.model = sweeps.decoder().modelOf(p.payload.data(), p.payload.size()) ==
                                      velodyne::Model::HDL32 ? "HDL32" : "VLP16";
      writer = std::make_unique<rawlog::RawlogWriter>(out, writer_params);
    }
    if (p.payload.size() == velodyne::kPositionPacketSize) {
      if (pending.empty()) writer->writePosition(p);
      else pending_gps.push_back(p);
      return;
    }
    if (closed > 0) flush();  // this packet holds the start of the next sweep
    pending.push_back(p);
  });
  while (sweeps.next()) sweeps.takeGpsFixes();
  const std::string err = sweeps.packets().errorMessage();
  if (sweeps.packets().stats().data_packets == 0 || !writer)
    throw std::runtime_error(err.empty() ? in + ": no Velodyne data packets" : err);
  sum.damage = damageWarning(sweeps);
  flush();
  writer->close();
  mrpt::config::CConfigFileMemory used;
  params.saveToConfigFile(used, "velodyne");
  writer_params.saveToConfigFile(used, "rawlog");
  writeFileAtomically(out + ".ini", "; the settings of the conversion of " + in + " (sources::convertToRawlog)\n" +
                                        used.getContent());
  sum.packets = writer->packetsWritten();
  sum.gps = writer->gpsWritten();
  if (const auto m = sweeps.lidarModel()) sum.lidar_model = m->model, sum.lidar_model_source = m->source;
  sum.warnings = sweeps.warnings();
  return sum;
}

}  // namespace roadslam::sources
