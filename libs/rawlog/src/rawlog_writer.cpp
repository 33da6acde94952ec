#include "roadslam/rawlog/rawlog_writer.h"

#include "roadslam/rawlog/gps_observation.h"

#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/gz_output.h"
#include "roadslam/common/param_table.h"
#include "roadslam/velodyne/position.h"

namespace roadslam::rawlog {

using mrpt::obs::CObservationVelodyneScan;
static_assert(sizeof(CObservationVelodyneScan::TVelodyneRawPacket) == velodyne::kDataPacketSize,
              "MRPT's packed packet struct must match the 1206-byte UDP payload");

void RawlogWriter::Params::fields(ParamTable& t) {
  t.text("sensor_label", sensor_label);
  t.text("gps_label", gps_label);
  t.text("model", model);
  t.text("calibration_file", calibration_file);
  t.num("min_range_m", min_range_m);
  t.num("max_range_m", max_range_m);
  t.num("x_m", x_m);
  t.num("y_m", y_m);
  t.num("z_m", z_m);
  t.angle("yaw_deg", yaw_rad);
  t.angle("pitch_deg", pitch_rad);
  t.angle("roll_deg", roll_rad);
}

void RawlogWriter::Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                                              const std::string& s) {
  loadFields(*this, c, s);
}

void RawlogWriter::Params::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                            const std::string& s) const {
  saveFields(*this, c, s);
}

struct RawlogWriter::Impl {
  explicit Impl(const std::string& p) : path(p), tmp(p) {}
  std::string path;
  TempFile tmp;  // removed unless close() commits it
  Params params;
  mrpt::obs::VelodyneCalibration calibration;
  std::unique_ptr<GzOutput> out;
  bool closed = false;

  /// Serializes \p obs; a write error surfaces as GzOutput's message (MRPT's archive may wrap it).
  template <typename T>
  void write(const T& obs) {
    try {
      mrpt::serialization::archiveFrom(*out) << obs;
    } catch (const std::exception& e) {
      throw std::runtime_error(out->error().empty() ? e.what() : out->error());
    }
  }
};

RawlogWriter::RawlogWriter(const std::string& path, const Params& params)
    : impl_(std::make_unique<Impl>(path)) {
  impl_->params = params;
  if (!params.calibration_file.empty()) {
    if (!impl_->calibration.loadFromXMLFile(params.calibration_file))
      throw std::runtime_error("cannot load Velodyne calibration XML '" + params.calibration_file + "'");
  } else {
    impl_->calibration = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration(params.model);
    if (impl_->calibration.empty())
      throw std::runtime_error("no default Velodyne calibration for model '" + params.model + "'");
  }
  impl_->out = std::make_unique<GzOutput>(impl_->tmp.path(), 1, path);
}

RawlogWriter::~RawlogWriter() = default;  // an unclosed rawlog's temporary file goes with Impl::tmp

void RawlogWriter::writeSweep(const std::vector<velodyne::RawPacket>& data_packets) {
  auto obs = CObservationVelodyneScan::Create();
  const Params& p = impl_->params;
  obs->sensorLabel = p.sensor_label;
  obs->sensorPose = mrpt::poses::CPose3D(p.x_m, p.y_m, p.z_m, p.yaw_rad, p.pitch_rad, p.roll_rad);
  obs->minRange = p.min_range_m;
  obs->maxRange = p.max_range_m;
  obs->calibration = impl_->calibration;
  obs->scan_packets.reserve(data_packets.size());
  for (const auto& pkt : data_packets) {
    if (pkt.payload.size() != velodyne::kDataPacketSize) {
      ++skipped_;
      continue;
    }
    if (obs->scan_packets.empty()) {
      obs->timestamp = mrpt::Clock::fromDouble(pkt.stamp_s);
      obs->originalReceivedTimestamp = obs->timestamp;
    }
    obs->scan_packets.emplace_back();
    std::memcpy(&obs->scan_packets.back(), pkt.payload.data(), velodyne::kDataPacketSize);
  }
  if (obs->scan_packets.empty()) return;
  impl_->write(*obs);
  packets_ += obs->scan_packets.size();
  ++sweeps_;
}

bool RawlogWriter::writePosition(const velodyne::RawPacket& position_packet) {
  velodyne::PositionPacket pos;
  if (!velodyne::decodePositionPacket(position_packet.payload.data(),
                                      position_packet.payload.size(), pos) ||
      !pos.fix) {
    ++skipped_;
    return false;
  }
  mrpt::obs::CObservationGPS obs;
  fillRmcObservation(*pos.fix, position_packet.stamp_s, impl_->params.gps_label, obs);
  impl_->write(obs);
  ++gps_;
  return true;
}

void RawlogWriter::writeGnss(const gnss::GnssFix& fix) {
  mrpt::obs::CObservationGPS obs;
  fillGnssObservation(fix, impl_->params.gps_label, obs);
  impl_->write(obs);
  ++gps_;
}

void RawlogWriter::close() {
  if (impl_->closed) return;
  impl_->out->close();
  impl_->closed = true;
  impl_->tmp.commit();
}

NmeaImportSummary nmeaLogToRawlog(const std::string& nmea_path, const std::string& rawlog_path,
                                  const std::string& label) {
  const gnss::NmeaLog log = gnss::readNmeaLog(nmea_path);
  RawlogWriter::Params p;
  p.gps_label = label;
  RawlogWriter w(rawlog_path, p);
  for (const auto& f : log.fixes) w.writeGnss(f);
  w.close();
  return {w.gpsWritten(), log.counters, log.problems};
}

}  // namespace roadslam::rawlog
