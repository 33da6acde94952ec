// Grabber lifecycle: session folder and files, receivers and sources, threads, stop and drain.
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>

#include "impl.h"
#include "roadslam/can/socketcan_source.h"
#include "roadslam/common/atomic_file.h"

namespace roadslam::grabber {
namespace fs = std::filesystem;

namespace {

/// Session files: the parameters actually used, and each sensor's calibration file (or a note
/// that MRPT's default calibration for the model is used).
void writeSessionFiles(const GrabParams& p, const std::string& dir) {
  mrpt::config::CConfigFileMemory cfg;
  p.saveToConfigFile(cfg);
  writeFileAtomically(dir + "/params_used.ini", cfg.getContent());
  for (const auto& s : p.sensors) {
    if (!s.scan.calibration_file.empty()) {
      std::error_code ec;
      fs::copy_file(s.scan.calibration_file, dir + "/" + s.section + ".calibration.xml",
                    fs::copy_options::overwrite_existing, ec);
      if (ec) throw std::runtime_error("cannot copy calibration '" + s.scan.calibration_file + "': " + ec.message());
    }
  }
}

}  // namespace

Grabber::Grabber(const GrabParams& params, const std::string& out_dir)
    : impl_(std::make_unique<Impl>()) {
  Impl& g = *impl_;
  g.params = params;
  g.out_dir = out_dir;
  for (const auto& sp : params.sensors) {
    auto rt = std::make_unique<SensorRt>(sp, params.writer.queue_capacity);
    rt->rx = std::make_unique<sources::UdpReceiver>(sp.udp);
    g.sensors.push_back(std::move(rt));
  }
  const CanParams& cp = params.can;
  if (cp.source != CanParams::Source::None) {
    g.can = std::make_unique<CanRt>(params.writer.can_queue_capacity);
    if (cp.source == CanParams::Source::Candump) {
      g.can->source = std::make_unique<can::LogReplaySource>(cp.candump_file, cp.candump_realtime);
      g.can->replay = true;
    } else {
      g.can->source = std::make_unique<can::SocketCanSource>(cp.socketcan);
    }
  }
  const GnssParams& gp = params.gnss;
  if (gp.source != GnssParams::Source::None) {
    g.gnss = std::make_unique<GnssRt>(params.writer.queue_capacity);
    if (gp.source == GnssParams::Source::Serial)
      g.gnss->source = std::make_unique<sources::SerialNmeaSource>(gp.device, gp.baud);
    else if (gp.source == GnssParams::Source::Gpsd)
      g.gnss->source = std::make_unique<sources::GpsdNmeaSource>(gp.gpsd_host, gp.gpsd_port, gp.gpsd_device);
    else {
      g.gnss->source = std::make_unique<sources::NmeaLogReplaySource>(gp.nmea_file, gp.replay_speed);
      g.gnss->replay = true;
    }
  }
  if (!out_dir.empty()) {  // only once every source opened: a failed start leaves no empty session folder
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec) throw std::runtime_error("cannot create output folder '" + out_dir + "': " + ec.message());
    writeSessionFiles(params, out_dir);
  }
  g.writer_task = makeWriter(g);
}

void Grabber::setObservationTap(ObservationTap tap) {
  if (impl_->started) throw std::logic_error("Grabber::setObservationTap after start()");
  impl_->tap = std::move(tap);
}

void Grabber::useCanSocket(int fd, const std::string& interface_name) {
  Impl& g = *impl_;
  if (g.started) throw std::logic_error("Grabber::useCanSocket after start()");
  if (!g.can) {
    // The writer opens the candump sidecar only when CAN is configured: rebuild it.
    g.can = std::make_unique<CanRt>(g.params.writer.can_queue_capacity);
    g.params.can.source = CanParams::Source::SocketCan;
    g.writer_task.reset();
    g.writer_task = makeWriter(g);
  }
  g.can->source = std::make_unique<can::SocketCanSource>(can::SocketCanSource::fromFd(fd, interface_name));
  g.can->replay = false;
}

Grabber::~Grabber() {
  try {
    stop();
  } catch (...) {
  }
}

void Grabber::start() {
  Impl& g = *impl_;
  if (g.started) return;
  g.started = true;
  g.start_s = wallNow();
  g.rate_prev_s = g.start_s;
  g.receiving = true;
  g.writing = true;
  for (auto& s : g.sensors) {
    s->last_packet_s = g.start_s;
    SensorRt* sp = s.get();
    s->thread = std::thread([&g, sp] {
      try {
        g.sensorLoop(*sp);
      } catch (const std::exception& e) {  // never silently: the watchdog reports it silent too
        std::lock_guard<std::mutex> lock(g.writer.text_mutex);
        if (g.writer.error.empty()) g.writer.error = sp->params.section + ": receiver stopped: " + e.what();
        g.writer.write_errors.fetch_add(1);
      }
    });
  }
  if (g.can) {
    g.can->last_frame_s = g.start_s;
    g.can->thread = std::thread([&g] { g.canLoop(); });
  }
  if (g.gnss) {
    g.gnss->last_line_s = g.start_s;
    g.gnss->thread = std::thread([&g] { g.gnssLoop(); });
  }
  g.writer_thread = std::thread([&g] { g.writer_task->run(); });
}

void Grabber::stop() {
  Impl& g = *impl_;
  if (!g.started || g.stopped) return;
  g.stopped = true;
  g.receiving = false;
  for (auto& s : g.sensors)
    if (s->thread.joinable()) s->thread.join();
  if (g.can && g.can->thread.joinable()) g.can->thread.join();
  if (g.gnss && g.gnss->thread.joinable()) g.gnss->thread.join();
  g.writing = false;  // the writer drains every queue, then closes the files
  if (g.writer_thread.joinable()) g.writer_thread.join();
  GrabStatus st = status();
  writeSummary(st);
  std::lock_guard<std::mutex> lock(impl_->status_mutex);
  impl_->held_events = std::move(st.events);  // the caller's next status() tells them
}

std::uint16_t Grabber::dataPort(std::size_t i) const { return impl_->sensors.at(i)->rx->dataPort(); }
std::uint16_t Grabber::positionPort(std::size_t i) const {
  return impl_->sensors.at(i)->rx->positionPort();
}

}  // namespace roadslam::grabber
