// Grabber::status (with the watchdog), the one-line status text and summary.json.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>

#include "impl.h"
#include "roadslam/common/atomic_file.h"

namespace roadslam::grabber {
namespace {

void gnssStatus(GnssRt& r, const GnssParams& p, bool running, double now, GrabStatus& st) {
  GnssStatus& o = st.gnss;
  o.enabled = true;
  o.source = r.source->describe();
  o.lines = r.lines;
  o.epochs = r.epochs;
  o.split_epochs = r.split_epochs;
  o.queue_drops = r.queue_drops;
  o.queue_depth = r.queue.size();
  o.queue_high_water = r.queue.highWater();
  {
    std::lock_guard<std::mutex> lock(r.mutex);
    o.nmea = r.nmea;
    o.problems = r.problems;
    o.quality = r.last_fix.quality;
    o.satellites = r.last_fix.satellites;
    o.hdop = r.last_fix.hdop;
    o.error = r.error;
  }
  const double quiet = now - r.last_line_s;
  if (running && !r.silent && quiet > p.silent_after_s) {
    r.silent = true;
    ++r.silent_events;
    st.events.push_back(fmt::format("GNSS: silent for {:.1f} s (no sentence from {})", quiet, o.source));
  } else if (r.silent && quiet <= p.silent_after_s) {
    r.silent = false;
    st.events.push_back("GNSS: receiving again");
  }
  o.silent = r.silent;
  o.silent_events = r.silent_events;
}

}  // namespace

GrabStatus Grabber::status() {
  Impl& g = *impl_;
  std::lock_guard<std::mutex> lock(g.status_mutex);
  GrabStatus st;
  st.events = std::move(g.held_events);
  g.held_events.clear();
  const double now = wallNow();
  st.elapsed_s = g.started ? now - g.start_s : 0;
  const double dt = std::max(1e-6, now - g.rate_prev_s);
  const bool running = g.started && !g.stopped;
  for (auto& s : g.sensors) {
    SensorStatus o;
    o.label = s->params.scan.sensor_label;
    o.data_port = s->rx->dataPort();
    o.position_port = s->rx->positionPort();
    o.packets = s->packets;
    o.data_packets = s->data_packets;
    o.position_packets = s->position_packets;
    o.malformed = s->malformed;
    o.foreign = s->foreign;
    o.missing = s->missing;
    o.kernel_drops = s->kernel_drops;
    o.queue_drops = s->queue_drops;
    o.sweeps = s->sweeps;
    o.pause_cuts = s->pause_cuts;
    o.queue_depth = s->queue.size();
    o.queue_high_water = s->queue.highWater();
    o.rate_pps = double(o.data_packets - s->rate_prev_packets) / dt;
    s->rate_prev_packets = o.data_packets;
    o.clock_offset_s = s->offset_s;
    o.clock_offset_min_s = o.packets ? s->offset_min_s.load() : 0;
    o.clock_offset_max_s = o.packets ? s->offset_max_s.load() : 0;
    // Watchdog: report the transition to silence and back, once each.
    const double quiet = now - s->last_packet_s;
    if (running && !s->silent && quiet > s->params.silent_after_s) {
      s->silent = true;
      ++s->silent_events;
      st.events.push_back(fmt::format("{}: silent for {:.1f} s (no packet on port {})", o.label, quiet,
                                      o.data_port));
    } else if (s->silent && quiet <= s->params.silent_after_s) {
      s->silent = false;
      st.events.push_back(fmt::format("{}: receiving again", o.label));
    }
    o.silent = s->silent;
    o.silent_events = s->silent_events;
    {
      std::lock_guard<std::mutex> model_lock(s->model_mutex);
      if (s->model) {
        o.lidar_model = velodyne::displayName(s->model->model);
        o.lidar_model_source = velodyne::toString(s->model->source);
        o.lidar_layout = s->model->layout.describe();
        if (!s->model->warning.empty() && !s->model_reported) st.events.push_back(o.label + ": warning: " + s->model->warning);
        s->model_reported = true;
      }
    }
    st.sensors.push_back(o);
  }
  if (g.can) {
    CanRt& c = *g.can;
    st.can.enabled = true;
    st.can.frames = c.frames;
    st.can.error_frames = c.error_frames;
    st.can.bus_off = c.bus_off;
    st.can.kernel_drops = c.kernel_drops;
    st.can.malformed = c.malformed;
    st.can.queue_drops = c.queue_drops;
    st.can.vehicle_observations = c.vehicle_obs;
    st.can.queue_depth = c.queue.size();
    st.can.queue_high_water = c.queue.highWater();
    st.can.rate_fps = double(st.can.frames - c.rate_prev_frames) / dt;
    c.rate_prev_frames = st.can.frames;
    const double quiet = now - c.last_frame_s;
    const double limit = g.params.can.silent_after_s;
    if (running && !c.silent && quiet > limit) {
      c.silent = true;
      ++c.silent_events;
      st.events.push_back(fmt::format("CAN: silent for {:.1f} s (no frame)", quiet));
    } else if (c.silent && quiet <= limit) {
      c.silent = false;
      st.events.push_back("CAN: receiving again");
    }
    st.can.silent = c.silent;
    st.can.silent_events = c.silent_events;
    std::lock_guard<std::mutex> el(c.error_mutex);
    st.can.error = c.error;
  }
  if (g.gnss) gnssStatus(*g.gnss, g.params.gnss, running, now, st);
  g.rate_prev_s = now;
  WriterStatus& w = st.writer;
  w.observations = g.writer.observations;
  w.sweeps = g.writer.sweeps;
  w.packets = g.writer.packets;
  w.gps = g.writer.gps;
  w.bytes = g.writer.bytes;
  w.segments = g.writer.segments;
  w.pending = g.writer.pending;
  w.late = g.writer.late;
  w.write_errors = g.writer.write_errors;
  std::lock_guard<std::mutex> tl(g.writer.text_mutex);
  w.current_segment = g.writer.current_segment;
  w.error = g.writer.error;
  return st;
}

std::string Grabber::formatStatus(const GrabStatus& s) {
  std::string line = fmt::format("[{:7.1f} s]", s.elapsed_s);
  for (const auto& o : s.sensors)
    line += fmt::format(" {}: {:.0f} pkt/s {} pkt, gaps {} ovfl {} qdrop {} q {}{} off {:+.3f} s |", o.label,
                        o.rate_pps, o.packets, o.missing, o.kernel_drops, o.queue_drops, o.queue_depth,
                        o.silent ? " SILENT" : "", o.clock_offset_s);
  if (s.can.enabled)
    line += fmt::format(" CAN: {:.0f} fr/s {} fr, err {} busoff {} drop {} q {}{} |", s.can.rate_fps,
                        s.can.frames, s.can.error_frames, s.can.bus_off,
                        s.can.kernel_drops + s.can.queue_drops, s.can.queue_depth,
                        s.can.silent ? " SILENT" : "");
  if (s.gnss.enabled)
    line += fmt::format(" GNSS: {} fixes, q {} sat {} hdop {:.1f}, bad {} nofix {}{} |", s.gnss.epochs,
                        s.gnss.quality, s.gnss.satellites, s.gnss.hdop,
                        s.gnss.nmea.bad_checksum + s.gnss.nmea.malformed, s.gnss.nmea.no_fix,
                        s.gnss.silent ? " SILENT" : "");
  if (s.writer.segments == 0)  // monitoring: the first segment of a recording opens with the Grabber
    line += fmt::format(" not recording: {} sweeps, pending {}", s.writer.sweeps, s.writer.pending);
  else
    line += fmt::format(" rawlog: {} sweeps, {:.1f} MB in {} file(s), pending {}", s.writer.sweeps,
                        double(s.writer.bytes) / 1e6, s.writer.segments, s.writer.pending);
  if (s.writer.write_errors) line += fmt::format(", {} WRITE ERRORS: {}", s.writer.write_errors, s.writer.error);
  return line;
}

namespace {
nlohmann::json gnssJson(const GnssStatus& g) {
  if (!g.enabled) return nullptr;
  nlohmann::json nmea = nlohmann::json::object();
  for (const auto& [name, n] : g.nmea.named()) nmea[name] = n;
  return {{"source", g.source},       {"lines", g.lines},
          {"epochs", g.epochs},       {"split_epochs", g.split_epochs},
          {"queue_drops", g.queue_drops}, {"queue_high_water", g.queue_high_water},
          {"nmea", nmea},             {"problems", g.problems},
          {"silent_events", g.silent_events}, {"error", g.error}};
}
}  // namespace

void Grabber::writeSummary(const GrabStatus& s) const {
  using nlohmann::json;
  if (impl_->out_dir.empty()) return;  // monitoring: nothing is written
  json sensors = json::array();
  std::uint64_t received = 0, dropped = 0;
  for (const auto& o : s.sensors) {
    received += o.packets;
    // Packets lost before the writer: sequence gaps cover the network and kernel drops (both
    // leave a hole in the sensor's timestamps); the queue drops happen after reception.
    dropped += o.queue_drops + std::max(o.missing, o.kernel_drops);
    sensors.push_back({{"label", o.label}, {"data_port", o.data_port}, {"position_port", o.position_port},
                       {"packets", o.packets}, {"data_packets", o.data_packets},
                       {"position_packets", o.position_packets}, {"malformed", o.malformed},
                       {"foreign", o.foreign}, {"missing", o.missing}, {"kernel_drops", o.kernel_drops},
                       {"queue_drops", o.queue_drops}, {"queue_high_water", o.queue_high_water},
                       {"sweeps_queued", o.sweeps}, {"pause_cuts", o.pause_cuts},
                       {"clock_offset_s", o.clock_offset_s}, {"clock_offset_min_s", o.clock_offset_min_s},
                       {"clock_offset_max_s", o.clock_offset_max_s}, {"silent_events", o.silent_events},
                       {"lidar_model", o.lidar_model}, {"lidar_model_source", o.lidar_model_source},
                       {"lidar_layout", o.lidar_layout}});
  }
  json j = {{"elapsed_s", s.elapsed_s},
            {"packets_received", received},
            {"packets_dropped", dropped},
            {"sweeps", s.writer.sweeps},
            {"packets_written", s.writer.packets},
            {"gps_written", s.writer.gps},
            {"observations", s.writer.observations},
            {"rawlog_bytes", s.writer.bytes},
            {"rawlog_segments", s.writer.segments},
            {"late_observations", s.writer.late},
            {"write_errors", s.writer.write_errors},
            {"write_error", s.writer.error},
            {"can_frames", s.can.frames},
            {"can_frames_dropped", s.can.kernel_drops + s.can.queue_drops},
            {"can_error_frames", s.can.error_frames},
            {"can_bus_off", s.can.bus_off},
            {"can_malformed", s.can.malformed},
            {"can_vehicle_observations", s.can.vehicle_observations},
            {"can_error", s.can.error},
            {"can_silent_events", s.can.silent_events},
            {"can_queue_high_water", s.can.queue_high_water},
            {"gnss", gnssJson(s.gnss)},
            {"sensors", sensors}};
  writeFileAtomically(impl_->out_dir + "/summary.json", j.dump(2) + "\n");
}

}  // namespace roadslam::grabber
