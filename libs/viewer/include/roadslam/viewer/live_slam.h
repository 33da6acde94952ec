#pragma once
/// \file live_slam.h
/// `roadslam-view --run-slam INI`: the pipeline's odometry over the recording being replayed, on a
/// thread of its own, each sweep's pose and status posted into the model as it comes (the window
/// draws what the replay time has reached). A user watches a config at work on their own drive.

#include <atomic>
#include <mutex>
#include <string>
#include <thread>

#include "roadslam/viewer/model.h"

namespace mrpt::obs {
class CObservation;
}

namespace roadslam::pipeline {
class LiveGnss;
}

namespace roadslam::viewer {

class LiveSlam {
 public:
  /// Checks \p config_ini (unknown keys: an error with file and line) and opens the recording
  /// before returning; throws std::runtime_error naming the file on a problem. Then runs on a thread.
  LiveSlam(const std::string& config_ini, const std::string& recording, ViewerModel& model);
  /// The odometry on a live sensor: \p sensor_label's sweeps as the live view's grabber taps them
  /// (post them with post(); close() once the feed stopped). Decoded with the config's [velodyne].
  LiveSlam(const std::string& config_ini, const std::string& sensor_label, const std::string& name, ViewerModel& model);
  /// Live: hands an observation to the odometry's source (thread-safe; a CObservationGPS goes to the
  /// GNSS correction, others than the sensor's sweeps are ignored).
  void post(const std::shared_ptr<mrpt::obs::CObservation>& obs);
  /// Live: no more observations; the odometry finishes what it has.
  void close();
  /// Stops the odometry between two sweeps and joins.
  ~LiveSlam();
  LiveSlam(const LiveSlam&) = delete;
  LiveSlam& operator=(const LiveSlam&) = delete;

  /// Blocks until a frame stamped at or after \p t_s was posted, or the recording ended (headless
  /// renders of a time), or \p timeout_s passed; false on the timeout.
  bool waitUntil(double t_s, double timeout_s = 1e9);
  bool done() const { return done_; }
  std::size_t frames() const { return frames_; }
  /// Live: the online GNSS correction of the odometry's poses (pipeline/live_gnss.h), fed by the
  /// CObservationGPS records posted (a grab ini's [gnss] receiver, a car's CAN_GPS); null on a recording.
  const pipeline::LiveGnss* gnss() const;
  /// The problem that stopped the odometry, if one did (empty otherwise).
  std::string error() const;

 private:
  struct Impl;
  void run(Impl& impl);

  ViewerModel& model_;
  std::unique_ptr<Impl> impl_;
  std::atomic<bool> stop_{false}, done_{false};
  std::atomic<std::size_t> frames_{0};
  std::atomic<double> last_stamp_s_{0.0};
  mutable std::mutex error_mutex_;
  std::string error_;
  std::thread thread_;
};

}  // namespace roadslam::viewer
