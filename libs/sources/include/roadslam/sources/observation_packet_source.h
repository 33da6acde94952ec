#pragma once
/// \file observation_packet_source.h
/// Packets of sweeps handed over as MRPT observations while they arrive (the live viewer's grabber
/// tap), as a PacketSource, so the odometry runs on a live sensor through the same SweepSource and
/// pipeline as on a recording. post() from any thread; next() waits a little for packets and says
/// nullopt-but-not-finished when none came; close() ends the stream once it is drained.

#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>

#include "roadslam/sources/packet_source.h"

namespace mrpt::obs {
class CObservation;
}

namespace roadslam::sources {

class ObservationPacketSource : public PacketSource {
 public:
  /// Takes the CObservationVelodyneScan of \p sensor_label (every other observation is ignored: CAN,
  /// GPS, another LiDAR); \p name for describe().
  ObservationPacketSource(std::string sensor_label, std::string name, const PortConfig& ports = {});

  /// Thread-safe: queues the packets of \p obs when it is a sweep of the sensor.
  void post(const std::shared_ptr<mrpt::obs::CObservation>& obs);
  /// Thread-safe: no more posts; finished() once what was posted is read.
  void close();

  /// The next packet; waits up to \p wait_s (0.1 s) for one.
  std::optional<velodyne::RawPacket> next() override;
  bool finished() const override;
  const SourceStats& stats() const override { return stats_; }
  std::string describe() const override { return name_; }
  double waitSeconds() const { return wait_s_; }

 private:
  std::string label_, name_;
  PortConfig ports_;
  double wait_s_ = 0.1;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<velodyne::RawPacket> queue_;
  bool closed_ = false;
  SourceStats stats_;          // reader's thread
  GapCounter gaps_;
};

}  // namespace roadslam::sources
