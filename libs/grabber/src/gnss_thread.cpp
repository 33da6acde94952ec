// GNSS thread: NmeaSource -> lines for the NMEA sidecar, and each completed receiver epoch as a
// CObservationGPS (rawlog::fillGnssObservation: receiver UTC in `timestamp`, host receive time in
// `originalReceivedTimestamp`). Parsing problems (checksums, no fix, time jumps, other datums) are
// counted by gnss::NmeaParser and never stop the thread.
#include <mrpt/obs/CObservationGPS.h>

#include "impl.h"
#include "roadslam/rawlog/gps_observation.h"

namespace roadslam::grabber {

namespace {
constexpr int kReadTimeout_ms = 50;  // bounds the reaction to stop() and the epoch-idle check
}

void Grabber::Impl::gnssLoop() {
  GnssRt& r = *gnss;
  const GnssParams& p = params.gnss;
  gnss::NmeaParser parser(gnss::NmeaParams{p.max_gap_s});
  double last_line_wall = 0, last_epoch_s = -1e300;
  bool open_epoch = false;
  auto publish = [&] {
    std::lock_guard<std::mutex> lock(r.mutex);
    r.nmea = parser.counters();
    r.problems = parser.problems();
  };
  auto take = [&](std::optional<gnss::GnssFix> f) {
    if (!f || !f->valid() || !f->has_position) return;
    const double t = f->stamp();
    if (t <= last_epoch_s) {  // the rest of an epoch cut by epoch_idle_s: its first part was written
      r.split_epochs.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    last_epoch_s = t;
    GnssItem it;
    it.obs = std::make_shared<mrpt::obs::CObservationGPS>();
    rawlog::fillGnssObservation(*f, p.label, *it.obs);
    it.stamp_s = f->t_receive_s;
    {
      std::lock_guard<std::mutex> lock(r.mutex);
      r.last_fix = *f;
    }
    r.epochs.fetch_add(1, std::memory_order_relaxed);
    if (!r.queue.tryPush(std::move(it))) r.queue_drops.fetch_add(1, std::memory_order_relaxed);
  };
  try {
    sources::NmeaLine l;
    while (receiving.load(std::memory_order_relaxed)) {
      const sources::NmeaRead st = r.source->read(l, kReadTimeout_ms);
      if (st == sources::NmeaRead::End) break;
      if (st == sources::NmeaRead::Timeout) {
        if (open_epoch && wallNow() - last_line_wall > p.epoch_idle_s) {
          take(parser.flush());
          publish();
          open_epoch = false;
        }
        continue;
      }
      last_line_wall = wallNow();
      if (r.replay && p.restamp) l.receive_s = last_line_wall;
      r.lines.fetch_add(1, std::memory_order_relaxed);
      r.last_line_s.store(last_line_wall, std::memory_order_relaxed);
      GnssItem line_item;
      line_item.line = l;
      line_item.stamp_s = l.receive_s;
      if (!r.queue.tryPush(std::move(line_item))) r.queue_drops.fetch_add(1, std::memory_order_relaxed);
      take(parser.feed(l.text, l.receive_s));
      open_epoch = true;
      publish();
    }
    take(parser.flush());
    publish();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.error = r.source->errorMessage();
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(r.mutex);
    r.error = e.what();
  }
  r.ended = true;
}

}  // namespace roadslam::grabber
