// Receiving thread of one LiDAR: UdpReceiver -> SweepGrouper -> bounded queue to the writer.
#include <algorithm>
#include <cmath>

#include "impl.h"

namespace roadslam::grabber {
namespace {

constexpr double kDrain_s = 0.3;  // longest drain of a socket at stop [s]

std::uint32_t readU32(const std::uint8_t* p) {
  return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
         (std::uint32_t(p[3]) << 24);
}

/// Host receive time minus the sensor's own time, both taken within the hour [s] (VLP-16 manual
/// 63-9243 section 9.3.1: the timestamp counts microseconds past the top of the hour).
double clockOffset_s(const velodyne::RawPacket& pkt, bool data) {
  const std::size_t at = data ? 1200 : velodyne::kPositionTimestampOffset;
  const double sensor_s = readU32(pkt.payload.data() + at) * 1e-6;
  double d = std::fmod(pkt.stamp_s, 3600.0) - sensor_s;
  if (d >= 1800) d -= 3600;
  if (d < -1800) d += 3600;
  return d;
}

void atomicMin(std::atomic<double>& a, double v) {
  if (v < a.load(std::memory_order_relaxed)) a.store(v, std::memory_order_relaxed);
}
void atomicMax(std::atomic<double>& a, double v) {
  if (v > a.load(std::memory_order_relaxed)) a.store(v, std::memory_order_relaxed);
}

/// Chooses the sensor's model from the layout seen so far (once): the summary's lidar_model and, with
/// model = auto and no calibration file, the calibration written with its sweeps.
void decideModel(SensorRt& s) {
  if (s.decided_model.load() != 0 || s.model) return;
  auto c = velodyne::chooseModel(s.params.udp.ports.model, s.layout.verdict(), "[" + s.params.section + "] model");
  std::lock_guard<std::mutex> lock(s.model_mutex);
  s.decided_model.store(static_cast<int>(c.model));
  s.model = std::move(c);
}

void pushOrCount(SensorRt& s, SensorItem&& item) {
  const std::size_t n = item.packets.size();
  if (n == 0) return;
  if (item.sweep) decideModel(s);  // the writer needs it for this sweep's calibration
  const bool sweep = item.sweep;
  if (s.queue.tryPush(std::move(item))) {
    if (sweep) s.sweeps.fetch_add(1, std::memory_order_relaxed);
  } else {
    s.queue_drops.fetch_add(n, std::memory_order_relaxed);
  }
}

void copyStats(SensorRt& s) {
  const sources::SourceStats& st = s.rx->stats();
  s.packets.store(st.packets, std::memory_order_relaxed);
  s.data_packets.store(st.data_packets, std::memory_order_relaxed);
  s.position_packets.store(st.position_packets, std::memory_order_relaxed);
  s.malformed.store(st.malformed_packets + s.bad_flag, std::memory_order_relaxed);
  s.foreign.store(st.skipped_packets + s.other_sender, std::memory_order_relaxed);
  s.missing.store(s.gaps.missing(), std::memory_order_relaxed);
  s.kernel_drops.store(st.kernel_drops, std::memory_order_relaxed);
  s.pause_cuts.store(s.grouper.revolutionsCut(), std::memory_order_relaxed);
}

}  // namespace

void Grabber::Impl::sensorLoop(SensorRt& s) {
  int self = 0;
  for (std::size_t i = 0; i < sensors.size(); ++i)
    if (sensors[i].get() == &s) self = int(i);
  const std::uint16_t data_port = s.rx->dataPort();
  const bool lock = s.params.lock_first_sender && s.params.udp.source_filter.empty();
  auto handle = [&](velodyne::RawPacket&& pkt) {
    if (lock) {
      if (!s.locked) {
        s.locked_ip = pkt.src_ip;
        s.locked = true;
      } else if (pkt.src_ip != s.locked_ip) {
        ++s.other_sender;  // a second sensor on the same port: would corrupt the sweeps
        return;
      }
    }
    s.last_packet_s.store(wallNow(), std::memory_order_relaxed);
    const bool data = pkt.dst_port == data_port;
    if (data) {
      if (!SweepGrouper::accepts(pkt)) {  // right size, not a Velodyne data packet
        ++s.bad_flag;
        return;
      }
      s.gaps.feed(pkt.payload.data());
      if (!s.layout.full()) {
        s.layout.add(pkt.payload.data(), pkt.payload.size());
        if (s.layout.full()) decideModel(s);
      }
    }
    const double off = clockOffset_s(pkt, data);
    s.offset_s.store(off, std::memory_order_relaxed);
    atomicMin(s.offset_min_s, off);
    atomicMax(s.offset_max_s, off);
    if (data) {
      if (s.grouper.add(std::move(pkt))) pushOrCount(s, SensorItem{self, true, s.grouper.take()});
    } else {
      SensorItem item{self, false, {}};
      item.packets.push_back(std::move(pkt));
      pushOrCount(s, std::move(item));
    }
  };
  while (receiving.load(std::memory_order_relaxed)) {
    auto pkt = s.rx->next();
    copyStats(s);
    if (pkt) {
      handle(std::move(*pkt));
    } else if (s.grouper.pending() > 0) {
      // A poll timeout without a packet (the sensor sends every 1.3 ms): it stopped. Hand over
      // the sweep in progress now, so it is written in time order and survives a crash.
      pushOrCount(s, SensorItem{self, true, s.grouper.takePartial()});
    }
  }
  // What the socket still holds at stop (bounded in time: a sender may never pause), then the
  // last, partial sweep.
  const double drain_until = wallNow() + kDrain_s;
  while (wallNow() < drain_until) {
    auto pkt = s.rx->next();
    if (!pkt) break;
    handle(std::move(*pkt));
  }
  copyStats(s);
  pushOrCount(s, SensorItem{self, true, s.grouper.takePartial()});
  decideModel(s);  // a sensor that sent no sweep: the set model, or none
}

}  // namespace roadslam::grabber
