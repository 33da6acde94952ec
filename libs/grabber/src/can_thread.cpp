// CAN thread: FrameSource -> bounded queue to the writer. Error frames (bus-off included) are
// counted and recorded like any frame: they are part of what happened on the bus.
#include <linux/can/error.h>

#include <chrono>

#include "impl.h"

namespace roadslam::grabber {

void Grabber::Impl::canLoop() {
  CanRt& c = *can;
  constexpr int kReadTimeout_ms = 50;  // bounds the reaction to stop()
  can::CanFrame f;
  try {
    while (receiving.load(std::memory_order_relaxed)) {
      const can::ReadStatus st = c.source->read(f, kReadTimeout_ms);
      const can::SourceStats& ss = c.source->stats();
      c.kernel_drops.store(ss.dropped, std::memory_order_relaxed);
      c.malformed.store(ss.malformed, std::memory_order_relaxed);
      if (st == can::ReadStatus::kEnd) break;
      if (st != can::ReadStatus::kFrame) continue;
      if (c.replay && params.can.restamp)
        f.t_us = std::chrono::duration_cast<std::chrono::microseconds>(
                     std::chrono::system_clock::now().time_since_epoch())
                     .count();
      c.frames.fetch_add(1, std::memory_order_relaxed);
      c.last_frame_s.store(wallNow(), std::memory_order_relaxed);
      if (f.error()) {
        c.error_frames.fetch_add(1, std::memory_order_relaxed);
        if (f.id & CAN_ERR_BUSOFF) c.bus_off.fetch_add(1, std::memory_order_relaxed);
      }
      if (!c.queue.tryPush(can::CanFrame(f))) c.queue_drops.fetch_add(1, std::memory_order_relaxed);
    }
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(c.error_mutex);
    c.error = e.what();
  }
  c.ended = true;
}

}  // namespace roadslam::grabber
