#include <roadslam/can/frame_source.h>

#include <chrono>
#include <thread>

namespace roadslam::can {
namespace {
std::int64_t wallMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
}  // namespace

LogReplaySource::LogReplaySource(const std::string& path, bool realtime, double speed)
    : reader_(path), realtime_(realtime), speed_(speed > 0 ? speed : 1.0) {}

ReadStatus LogReplaySource::read(CanFrame& frame, int timeout_ms) {
  if (!reader_.next(frame)) {
    stats_.dropped = reader_.stats().bad;
    stats_.malformed = reader_.stats().bad;
    return ReadStatus::kEnd;
  }
  stats_.dropped = stats_.malformed = reader_.stats().bad;
  ++stats_.frames;
  if (frame.error()) ++stats_.error_frames;
  if (!realtime_) return ReadStatus::kFrame;
  if (first_log_us_ < 0) {
    first_log_us_ = frame.t_us;
    first_wall_us_ = wallMicros();
    return ReadStatus::kFrame;
  }
  // Recorded spacing divided by speed; a timeout shorter than the wait is honoured by sleeping
  // only that long and then still returning the frame (replay never loses frames).
  const auto due = first_wall_us_ + static_cast<std::int64_t>(static_cast<double>(frame.t_us - first_log_us_) / speed_);
  std::int64_t wait = due - wallMicros();
  if (timeout_ms >= 0 && wait > static_cast<std::int64_t>(timeout_ms) * 1000) wait = static_cast<std::int64_t>(timeout_ms) * 1000;
  if (wait > 0) std::this_thread::sleep_for(std::chrono::microseconds(wait));
  return ReadStatus::kFrame;
}

}  // namespace roadslam::can
