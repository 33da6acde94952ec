#pragma once
// Private state of a Grabber shared by its threads (grabber.cpp, sensor_thread.cpp,
// can_thread.cpp, writer_thread.cpp).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "roadslam/can/frame.h"
#include "roadslam/can/frame_source.h"
#include "roadslam/grabber/bounded_queue.h"
#include "roadslam/grabber/grabber.h"
#include "roadslam/grabber/sweep_grouper.h"
#include "roadslam/gnss/nmea.h"
#include "roadslam/sources/nmea_source.h"
#include "roadslam/sources/udp_receiver.h"
#include "roadslam/velodyne/model_choice.h"

namespace mrpt::obs {
class CObservationGPS;
}

namespace roadslam::grabber {

/// Host wall clock, the clock of the kernel receive stamps [s since epoch].
inline double wallNow() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

/// A sweep (data packets) or one position packet of sensor `sensor`, for the writer.
struct SensorItem {
  int sensor = 0;
  bool sweep = true;
  std::vector<velodyne::RawPacket> packets;
};

/// Run-time state of one LiDAR. Counters are written by its thread and read by status().
struct SensorRt {
  SensorParams params;
  std::unique_ptr<sources::UdpReceiver> rx;
  SweepGrouper grouper;
  sources::GapCounter gaps;          // on the recorded packets only (not a foreign sender's)
  std::uint32_t locked_ip = 0;       // lock_first_sender: the sender being recorded
  bool locked = false;
  std::uint64_t other_sender = 0;    // packets of another sender, not recorded
  std::uint64_t bad_flag = 0;        // 1206-byte data payloads without the 0xEEFF block flag
  velodyne::LayoutDetector layout;   // the first data packets' layout (sensor thread)
  // The model chosen from it (velodyne/model_choice.h), once, by the sensor thread: before its first
  // sweep goes to the writer, or when the layout window is full. decided_model: its Model value for
  // the writer's calibration (0 = not yet).
  std::mutex model_mutex;
  std::optional<velodyne::ModelChoice> model;
  std::atomic<int> decided_model{0};
  bool model_reported = false;       // its warning went out as a status event (under Impl::status_mutex)
  BoundedQueue<SensorItem> queue;
  std::thread thread;
  std::atomic<std::uint64_t> packets{0}, data_packets{0}, position_packets{0}, malformed{0},
      foreign{0}, missing{0}, kernel_drops{0}, queue_drops{0}, sweeps{0}, pause_cuts{0};
  std::atomic<double> last_packet_s{0};  // host time of the last packet [s]
  std::atomic<double> offset_s{0}, offset_min_s{1e300}, offset_max_s{-1e300};
  // status() bookkeeping (under Impl::status_mutex)
  std::uint64_t rate_prev_packets = 0;
  bool silent = false;
  std::uint64_t silent_events = 0;

  SensorRt(const SensorParams& p, std::size_t capacity)
      : params(p), gaps(p.udp.packet_period_s, p.udp.ports.model), queue(capacity) {}
};

struct CanRt {
  std::unique_ptr<can::FrameSource> source;
  bool replay = false;  // a candump log: restamp per CanParams::restamp
  BoundedQueue<can::CanFrame> queue;
  std::thread thread;
  std::atomic<std::uint64_t> frames{0}, error_frames{0}, bus_off{0}, kernel_drops{0}, malformed{0},
      queue_drops{0}, vehicle_obs{0};
  std::atomic<bool> ended{false};
  std::mutex error_mutex;
  std::string error;
  std::uint64_t rate_prev_frames = 0;
  std::atomic<double> last_frame_s{0};  // host time of the last frame [s]
  bool silent = false;                  // watchdog state (under Impl::status_mutex)
  std::uint64_t silent_events = 0;

  explicit CanRt(std::size_t capacity) : queue(capacity) {}
};

/// A GNSS line for the NMEA sidecar, or (obs set) a completed receiver epoch for the rawlog.
struct GnssItem {
  sources::NmeaLine line;
  std::shared_ptr<mrpt::obs::CObservationGPS> obs;
  double stamp_s = 0;  ///< host receive time: of the line, or of the epoch's first sentence [s]
};

struct GnssRt {
  std::unique_ptr<sources::NmeaSource> source;
  bool replay = false;  // an NMEA log: restamp per GnssParams::restamp
  BoundedQueue<GnssItem> queue;
  std::thread thread;
  std::atomic<std::uint64_t> lines{0}, epochs{0}, queue_drops{0}, split_epochs{0};
  std::atomic<double> last_line_s{0};  // host time of the last line [s]
  std::mutex mutex;                    // guards the fields below
  gnss::NmeaCounters nmea;             // the parser's counters, copied after each line
  std::vector<std::string> problems;   // the parser's first problems
  gnss::GnssFix last_fix;              // the last valid epoch
  std::string error;                   // why the source stopped, if it did
  std::atomic<bool> ended{false};
  bool silent = false;                 // watchdog state (under Impl::status_mutex)
  std::uint64_t silent_events = 0;

  explicit GnssRt(std::size_t capacity) : queue(capacity) {}
};

/// Writer counters, written by the writer thread only.
struct WriterCounters {
  std::atomic<std::uint64_t> observations{0}, sweeps{0}, packets{0}, gps{0}, bytes{0}, late{0},
      write_errors{0};
  std::atomic<std::size_t> segments{0}, pending{0};
  std::mutex text_mutex;
  std::string current_segment, error;
};

/// The writer thread's body (writer_thread.cpp); built in the Grabber constructor so that file
/// errors surface there.
class WriterTask {
 public:
  virtual ~WriterTask() = default;
  virtual void run() = 0;
};
std::unique_ptr<WriterTask> makeWriter(Grabber::Impl& g);

struct Grabber::Impl {
  GrabParams params;
  std::string out_dir;  // empty: monitoring, nothing written
  ObservationTap tap;
  std::vector<std::unique_ptr<SensorRt>> sensors;
  std::unique_ptr<CanRt> can;
  std::unique_ptr<GnssRt> gnss;
  WriterCounters writer;
  std::unique_ptr<WriterTask> writer_task;
  std::thread writer_thread;
  std::atomic<bool> receiving{false};  // receivers run while true
  std::atomic<bool> writing{false};    // writer runs while true, then drains
  bool started = false, stopped = false;
  double start_s = 0;
  std::mutex status_mutex;
  std::vector<std::string> held_events;  // status events of stop()'s own status() call, for the next caller
  double rate_prev_s = 0;

  void sensorLoop(SensorRt& s);
  void canLoop();
  void gnssLoop();
};

}  // namespace roadslam::grabber
