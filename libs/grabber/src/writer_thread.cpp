// Writer thread: merges the sensor and CAN queues in time order into the rawlog segments and
// writes the lossless sidecars. The only thread that touches the disk.
#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>
#include <thread>

#include "impl.h"
#include "roadslam/can/candump.h"
#include "roadslam/grabber/segment_writer.h"
#include "roadslam/pcap/pcap_writer.h"
#include "roadslam/rawlog/gps_observation.h"
#include "roadslam/vehicle/dead_reckoning.h"
#include "roadslam/vehicle/rawlog_export.h"
#include "roadslam/velodyne/position.h"

namespace roadslam::grabber {
namespace {

using mrpt::obs::CObservationVelodyneScan;
static_assert(sizeof(CObservationVelodyneScan::TVelodyneRawPacket) == velodyne::kDataPacketSize,
              "MRPT's packed packet struct must match the 1206-byte UDP payload");
constexpr auto kIdleSleep = std::chrono::milliseconds(2);

/// An observation waiting for its turn: a sensor item, a CAN frame (sensor < 0, no obs), or an
/// observation already made (obs: a GNSS epoch).
struct Pending {
  int sensor = -1;
  SensorItem item;
  can::CanFrame frame;
  std::shared_ptr<mrpt::obs::CObservation> obs;
};

class Writer : public WriterTask {
 public:
  explicit Writer(Grabber::Impl& g);
  ~Writer() override {
    try {
      closeSidecars();
    } catch (...) {
    }
  }
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;
  void run() override;

 private:
  bool drainQueues();
  void emitUpTo(double stamp_s);
  void emit(Pending& p);
  void writeSweep(const SensorItem& it);
  void writePosition(const SensorItem& it);
  void writeVehicle(const can::CanFrame& f);
  void writeObs(const std::shared_ptr<mrpt::obs::CObservation>& o);
  /// The calibration stored with sensor \p i's sweeps: its calibration file, the set model's, or
  /// (model = auto) that of the model its packets showed (SensorRt::decided_model).
  const mrpt::obs::VelodyneCalibration& calibrationOf(int i);
  void flushAll();
  void updateCounters();
  void openSidecars();
  void closeSidecars();
  /// Runs \p f; a write error (disk full, I/O error) is counted and the first one kept:
  /// recording goes on, what could not be written is lost and said so.
  template <class F>
  void guarded(F&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      if (g_.writer.write_errors.fetch_add(1) == 0) {
        std::lock_guard<std::mutex> lock(g_.writer.text_mutex);
        g_.writer.error = e.what();
      }
    }
  }

  Grabber::Impl& g_;
  std::unique_ptr<SegmentWriter> seg_;  // null when monitoring
  std::vector<mrpt::obs::VelodyneCalibration> calib_;
  std::optional<mrpt::obs::VelodyneCalibration> hdl32_default_;  // loaded when a sensor on auto shows one
  std::vector<std::unique_ptr<pcap::PcapWriter>> pcap_;
  std::FILE* candump_ = nullptr;
  std::FILE* nmea_ = nullptr;  // gnss_NNN.nmea.log: the libs/gnss/nmea.h log format
  std::size_t sidecar_segment_ = 0;  // the sidecars follow the rawlog segment index
  std::unique_ptr<vehicle::VehicleDecoder> decoder_;
  std::unique_ptr<vehicle::DeadReckoning> dr_;
  vehicle::VehicleState vstate_;
  std::multimap<double, Pending> pending_;
  double last_emitted_s_ = -1e300;
  double last_flush_s_ = 0;
};

SegmentPolicy policyOf(const WriterParams& w) {
  SegmentPolicy p;
  p.max_size_bytes = w.rotate_size_bytes;
  p.max_age_s = w.rotate_period_s;
  p.compression_level = w.compression_level;
  return p;
}

Writer::Writer(Grabber::Impl& g)
    : g_(g) {
  if (!g.out_dir.empty())
    seg_ = std::make_unique<SegmentWriter>(g.out_dir, g.params.writer.file_prefix, policyOf(g.params.writer));
  for (const auto& s : g.params.sensors) {
    mrpt::obs::VelodyneCalibration c;
    if (!s.scan.calibration_file.empty()) {
      if (!c.loadFromXMLFile(s.scan.calibration_file))
        throw std::runtime_error("[" + s.section + "] calibration_file: cannot load '" +
                                 s.scan.calibration_file + "'");
    } else {
      c = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration(s.scan.model);
    }
    calib_.push_back(c);
  }
  openSidecars();
  if (g.can) {
    if (!g.params.can.vehicle_ini.empty()) {
      const auto vp = vehicle::loadVehicleIni(g.params.can.vehicle_ini, g.params.can.data_root);
      decoder_ = std::make_unique<vehicle::VehicleDecoder>(vp);
      dr_ = std::make_unique<vehicle::DeadReckoning>(vehicle::DeadReckoningParams{}, vp);
    }
  }
  updateCounters();
}

void Writer::run() {
  last_flush_s_ = wallNow();
  for (;;) {
    const bool writing = g_.writing.load();
    const bool got = drainQueues();
    const double now = wallNow();
    if (writing) {
      emitUpTo(now - g_.params.writer.reorder_window_s);
    } else if (!got) {  // stopping and every queue is empty: write the rest and close
      emitUpTo(1e300);
      break;
    }
    if (now - last_flush_s_ >= g_.params.writer.flush_period_s) {
      flushAll();
      last_flush_s_ = now;
    }
    updateCounters();
    if (!got) std::this_thread::sleep_for(kIdleSleep);
  }
  flushAll();
  if (seg_) guarded([&] { seg_->close(); });
  guarded([&] { closeSidecars(); });
  updateCounters();
}

// Sidecars are cut with the rawlog segments: <sensor>_NNN.pcap and can_NNN.candump.log hold the
// packets / frames that arrived while grab_NNN.rawlog was the current segment.
void Writer::openSidecars() {
  if (!seg_) return;
  char idx[16];
  std::snprintf(idx, sizeof(idx), "_%03zu", sidecar_segment_);
  if (g_.params.writer.pcap_sidecar)
    for (const auto& s : g_.params.sensors)
      pcap_.push_back(std::make_unique<pcap::PcapWriter>(g_.out_dir + "/" + s.section + idx + ".pcap"));
  if (g_.can && g_.params.writer.candump_sidecar) {
    const std::string path = g_.out_dir + "/can" + idx + ".candump.log";
    candump_ = std::fopen(path.c_str(), "w");
    if (!candump_) throw std::runtime_error("cannot create '" + path + "'");
  }
  if (g_.gnss && g_.params.writer.nmea_sidecar) {
    const std::string path = g_.out_dir + "/gnss" + idx + ".nmea.log";
    nmea_ = std::fopen(path.c_str(), "w");
    if (!nmea_) throw std::runtime_error("cannot create '" + path + "'");
  }
}

void Writer::closeSidecars() {
  for (auto& p : pcap_) p->close();
  pcap_.clear();
  if (candump_) std::fclose(candump_);
  candump_ = nullptr;
  if (nmea_) std::fclose(nmea_);
  nmea_ = nullptr;
}

bool Writer::drainQueues() {
  bool got = false;
  for (auto& s : g_.sensors) {
    SensorItem it;
    while (s->queue.tryPop(it)) {
      got = true;
      if (!pcap_.empty()) {
        guarded([&] {
          for (const auto& p : it.packets) {
            const uint16_t port = it.sweep ? velodyne::kDefaultDataPort : velodyne::kDefaultPositionPort;
            pcap_[std::size_t(it.sensor)]->writeUdp(p.stamp_s, port, port, p.payload.data(),
                                                    p.payload.size(), p.src_ip ? p.src_ip : 0xC0A801C9u);
          }
        });
      }
      const double t = it.packets.front().stamp_s;
      Pending p;
      p.sensor = it.sensor;
      p.item = std::move(it);
      pending_.emplace(t, std::move(p));
    }
  }
  if (g_.can) {
    Pending p;
    while (g_.can->queue.tryPop(p.frame)) {
      got = true;
      if (candump_) {
        char line[256];
        const std::size_t n = can::formatCandumpLine(p.frame, line, sizeof(line));
        std::fwrite(line, 1, n, candump_);
      }
      if (decoder_) pending_.emplace(p.frame.timeSeconds(), p);
    }
  }
  if (g_.gnss) {
    GnssItem it;
    while (g_.gnss->queue.tryPop(it)) {
      got = true;
      if (!it.obs) {
        if (nmea_) std::fprintf(nmea_, "%.6f %s\n", it.line.receive_s, it.line.text.c_str());
        continue;
      }
      Pending p;
      p.obs = std::move(it.obs);
      pending_.emplace(it.stamp_s, std::move(p));
    }
  }
  return got;
}

void Writer::emitUpTo(double stamp_s) {
  while (!pending_.empty() && pending_.begin()->first <= stamp_s) {
    auto node = pending_.extract(pending_.begin());
    if (node.key() < last_emitted_s_) g_.writer.late.fetch_add(1);
    last_emitted_s_ = std::max(last_emitted_s_, node.key());
    emit(node.mapped());
  }
}

void Writer::emit(Pending& p) {
  guarded([&] {
    if (p.obs) {
      writeObs(p.obs);
      g_.writer.gps.fetch_add(1);
    } else if (p.sensor < 0) writeVehicle(p.frame);
    else if (p.item.sweep) writeSweep(p.item);
    else writePosition(p.item);
  });
}

void Writer::writeObs(const std::shared_ptr<mrpt::obs::CObservation>& o) {
  if (seg_) {
    seg_->write(*o, wallNow());
    if (seg_->segments().size() - 1 != sidecar_segment_) {
      closeSidecars();
      sidecar_segment_ = seg_->segments().size() - 1;
      openSidecars();
    }
  }
  g_.writer.observations.fetch_add(1);
  if (g_.tap) g_.tap(o);
}

const mrpt::obs::VelodyneCalibration& Writer::calibrationOf(int i) {
  const SensorParams& sp = g_.params.sensors[std::size_t(i)];
  const bool by_packets = sp.scan.calibration_file.empty() && sp.udp.ports.model == velodyne::Model::Unknown;
  if (!by_packets || g_.sensors[std::size_t(i)]->decided_model.load() != int(velodyne::Model::HDL32))
    return calib_[std::size_t(i)];  // the set model's, or VLP16 (params.cpp's default for auto)
  if (!hdl32_default_) hdl32_default_ = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration("HDL32");
  return *hdl32_default_;
}

void Writer::writeSweep(const SensorItem& it) {
  const SensorParams& sp = g_.params.sensors[std::size_t(it.sensor)];
  const rawlog::RawlogWriter::Params& p = sp.scan;
  auto obs = std::make_shared<CObservationVelodyneScan>();
  obs->sensorLabel = p.sensor_label;
  obs->sensorPose = mrpt::poses::CPose3D(p.x_m, p.y_m, p.z_m, p.yaw_rad, p.pitch_rad, p.roll_rad);
  obs->minRange = p.min_range_m;
  obs->maxRange = p.max_range_m;
  obs->calibration = calibrationOf(it.sensor);
  obs->timestamp = mrpt::Clock::fromDouble(it.packets.front().stamp_s);
  obs->originalReceivedTimestamp = obs->timestamp;
  obs->scan_packets.resize(it.packets.size());
  for (std::size_t i = 0; i < it.packets.size(); ++i)
    std::memcpy(&obs->scan_packets[i], it.packets[i].payload.data(), velodyne::kDataPacketSize);
  writeObs(obs);
  g_.writer.sweeps.fetch_add(1);
  g_.writer.packets.fetch_add(it.packets.size());
}

// Same $GPRMC -> CObservationGPS mapping as rawlog::RawlogWriter (MRPT's parse_NMEA fields).
void Writer::writePosition(const SensorItem& it) {
  const velodyne::RawPacket& pkt = it.packets.front();
  velodyne::PositionPacket pos;
  if (!velodyne::decodePositionPacket(pkt.payload.data(), pkt.payload.size(), pos) || !pos.fix)
    return;  // kept in the pcap sidecar; nothing to put in an MRPT GPS record
  auto obs = std::make_shared<mrpt::obs::CObservationGPS>();
  rawlog::fillRmcObservation(*pos.fix, pkt.stamp_s, g_.params.sensors[std::size_t(it.sensor)].scan.gps_label, *obs);
  writeObs(obs);
  g_.writer.gps.fetch_add(1);
}

// The observations of vehicle::exportRawlog, one frame at a time (rawlog_export.h).
void Writer::writeVehicle(const can::CanFrame& f) {
  using vehicle::bit;
  using vehicle::Quantity;
  const vehicle::UpdateMask mask = decoder_->process(f, vstate_);
  if (!mask) return;
  const auto t = mrpt::Clock::fromDouble(f.timeSeconds());
  if (dr_->update(vstate_, mask)) {
    auto odo = std::make_shared<mrpt::obs::CObservationOdometry>();
    odo->sensorLabel = "CAN_ODOMETRY";
    odo->timestamp = t;
    const vehicle::Pose2D& p = dr_->pose();
    odo->odometry = mrpt::poses::CPose2D(p.x_m, p.y_m, p.yaw_rad);
    odo->hasVelocities = true;
    odo->velocityLocal = mrpt::math::TTwist2D(p.v_mps, 0.0, p.w_radps);
    writeObs(odo);
    g_.can->vehicle_obs.fetch_add(1);
  }
  constexpr vehicle::UpdateMask kImu =
      bit(Quantity::kYawRate) | bit(Quantity::kAccelX) | bit(Quantity::kAccelY);
  if (mask & kImu) {
    auto imu = std::make_shared<mrpt::obs::CObservationIMU>();
    imu->sensorLabel = "CAN_IMU";
    imu->timestamp = t;
    if (mask & bit(Quantity::kYawRate)) imu->set(mrpt::obs::IMU_WZ, vstate_.value(Quantity::kYawRate));
    if (mask & bit(Quantity::kAccelX)) imu->set(mrpt::obs::IMU_X_ACC, vstate_.value(Quantity::kAccelX));
    if (mask & bit(Quantity::kAccelY)) imu->set(mrpt::obs::IMU_Y_ACC, vstate_.value(Quantity::kAccelY));
    writeObs(imu);
    g_.can->vehicle_obs.fetch_add(1);
  }
  if (vehicle::gpsUpdated(vstate_, mask)) {
    writeObs(vehicle::gpsObservation(vstate_, "CAN_GPS"));
    g_.can->vehicle_obs.fetch_add(1);
  }
}

void Writer::flushAll() {
  if (seg_) guarded([&] { seg_->syncFlush(); });
  guarded([&] {
    for (auto& p : pcap_) p->flush();
  });
  if (candump_ && std::fflush(candump_) != 0)
    guarded([] { throw std::runtime_error("write error on the candump sidecar"); });
  if (nmea_ && std::fflush(nmea_) != 0)
    guarded([] { throw std::runtime_error("write error on the NMEA sidecar"); });
}

void Writer::updateCounters() {
  g_.writer.pending = pending_.size();
  if (!seg_) return;
  g_.writer.bytes = seg_->totalBytes();
  g_.writer.segments = seg_->segments().size();
  std::lock_guard<std::mutex> lock(g_.writer.text_mutex);
  if (!seg_->segments().empty()) g_.writer.current_segment = seg_->segments().back();
}

}  // namespace

std::unique_ptr<WriterTask> makeWriter(Grabber::Impl& g) { return std::make_unique<Writer>(g); }

}  // namespace roadslam::grabber
