#pragma once
/// \file frame_source.h
/// One interface for every source of CAN frames, live or recorded: SocketCAN raw sockets
/// (socketcan_source.h) and candump-log replay (below). Consumers never know which one they read.

#include <roadslam/can/candump.h>
#include <roadslam/can/frame.h>

#include <cstddef>
#include <memory>
#include <string>

namespace roadslam::can {

enum class ReadStatus { kFrame, kTimeout, kEnd };

/// Counters every source keeps; reported at the end of a run.
struct SourceStats {
  std::size_t frames = 0;         ///< frames returned
  std::size_t error_frames = 0;   ///< of which error frames (CAN_ERR_FLAG)
  std::size_t dropped = 0;        ///< frames the kernel dropped (SO_RXQ_OVFL), or bad log lines
  std::size_t malformed = 0;      ///< datagrams of an unexpected size / unparsable lines
  std::size_t reopens = 0;        ///< times the socket was reopened after the interface went down
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  /// Waits up to \p timeout_ms (-1: forever) for the next frame. Per-frame problems are counted in
  /// stats(), never thrown.
  virtual ReadStatus read(CanFrame& frame, int timeout_ms) = 0;
  virtual const SourceStats& stats() const = 0;
};

/// Replays a candump log, as fast as possible or at the recorded timing (scaled by \p speed).
class LogReplaySource : public FrameSource {
 public:
  /// \param realtime  sleep so frames come at their recorded spacing / speed
  LogReplaySource(const std::string& path, bool realtime = false, double speed = 1.0);
  ReadStatus read(CanFrame& frame, int timeout_ms) override;
  const SourceStats& stats() const override { return stats_; }
  const CandumpStats& logStats() const { return reader_.stats(); }

 private:
  CandumpReader reader_;
  bool realtime_;
  double speed_;
  std::int64_t first_log_us_ = -1;
  std::int64_t first_wall_us_ = 0;
  SourceStats stats_;
};

}  // namespace roadslam::can
