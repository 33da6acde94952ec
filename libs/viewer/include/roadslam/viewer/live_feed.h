#pragma once
/// \file live_feed.h
/// The live sources of `roadslam-view --udp PORT` and `--grab INI`: a grabber::Grabber (the same
/// receivers, sweep grouping, CAN decoding and time ordering as roadslam-grab) whose observations
/// go to the viewer through its tap, for the operator on the car. Without a record folder nothing is
/// written; with one (`--record DIR`) the session is recorded exactly as roadslam-grab records it.

#include <cstdint>
#include <memory>
#include <string>

#include "roadslam/grabber/grabber.h"
#include "roadslam/sources/live_observations.h"

namespace roadslam::viewer {

struct LiveRequest {
  int udp_port = -1;        ///< --udp PORT: one VLP-16 on this data port (position: 8308 with 2368, else none)
  std::string grab_ini;     ///< --grab INI: every LiDAR and the CAN source of a roadslam-grab ini
  std::string record_dir;   ///< --record DIR: also record the session there (roadslam-grab's files)
};

/// The grabber parameters for \p req: a one-sensor ini for --udp, the grab ini otherwise. Throws
/// std::runtime_error naming the ini (file, key) or the port on a bad value.
grabber::GrabParams liveParams(const LiveRequest& req);

class LiveFeed {
 public:
  /// Opens the sockets (and the CAN source) and starts receiving into \p sink (and \p also, e.g. the
  /// live odometry); throws naming the port, interface or file that cannot be opened.
  LiveFeed(const LiveRequest& req, sources::LiveObservations& sink, grabber::ObservationTap also = {});
  ~LiveFeed();  ///< stops (and, recording, closes the session's files)
  LiveFeed(const LiveFeed&) = delete;
  LiveFeed& operator=(const LiveFeed&) = delete;

  /// "UDP port 2368" or "grab ini PATH" (+ ", recording into DIR").
  const std::string& name() const { return name_; }
  /// The sensor label of the first LiDAR (the one a live odometry follows).
  static std::string firstSensorLabel(const LiveRequest& req) { return liveParams(req).sensors.at(0).scan.sensor_label; }
  /// The grabber's one-line status (packets, sweeps, CAN frames, drops, silent sensors).
  std::string statusLine();
  grabber::GrabStatus status() { return grabber_->status(); }
  /// Stops receiving and, recording, writes the rest; idempotent.
  void stop();

 private:
  std::unique_ptr<grabber::Grabber> grabber_;
  std::string name_;
};

}  // namespace roadslam::viewer
