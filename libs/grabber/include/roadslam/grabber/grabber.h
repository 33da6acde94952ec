#pragma once
/// \file grabber.h
/// Live recording session (in the spirit of MRPT's rawlog-grabber), all clocks the host's:
///  - one receiving thread per LiDAR (sources::UdpReceiver: data + position port, kernel receive
///    stamps), grouping data packets into sweeps (SweepGrouper);
///  - one CAN thread (SocketCAN, or a candump log / an open socket for tests);
///  - one GNSS thread (NMEA 0183 from a serial port or gpsd, or an NMEA log replayed), each receiver
///    epoch a CObservationGPS with the receiver's UTC and the host receive time;
///  - one writer thread that merges everything in time order into the rawlog segments
///    (SegmentWriter: CObservationVelodyneScan per sweep with the raw packets, CObservationGPS per
///    position packet, vehicle observations from libs/vehicle) and the lossless sidecars
///    (<sensor>.pcap, can.candump.log, gnss.nmea.log).
/// Receivers never wait for the disk: queues are bounded and what does not fit is counted as
/// dropped. A status snapshot is available at any time (status()); stop() drains and closes.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "roadslam/gnss/nmea.h"
#include "roadslam/grabber/params.h"

namespace mrpt::obs {
class CObservation;
}

namespace roadslam::grabber {

/// Receives every observation the writer emits, in time order, on the writer thread (it must not
/// block: the viewer's live mode queues it for its drawing thread).
using ObservationTap = std::function<void(const std::shared_ptr<mrpt::obs::CObservation>&)>;

/// Counters of one LiDAR (a consistent-enough snapshot: each field is read atomically).
struct SensorStatus {
  std::string label;
  std::uint16_t data_port = 0, position_port = 0;  ///< bound [UDP port]
  std::uint64_t packets = 0;            ///< data + position packets received [count]
  std::uint64_t data_packets = 0, position_packets = 0;
  std::uint64_t malformed = 0;          ///< wrong size on a Velodyne port [count]
  std::uint64_t foreign = 0;            ///< from another sender than source_filter / the locked first sender [count]
  std::uint64_t missing = 0;            ///< sequence gaps from the sensor's own timestamps [count]
  std::uint64_t kernel_drops = 0;       ///< socket buffer overflows (SO_RXQ_OVFL) [count]
  std::uint64_t queue_drops = 0;        ///< packets dropped because the writer queue was full [count]
  std::uint64_t sweeps = 0;             ///< sweeps queued for writing [count]
  /// Revolutions recorded as two observations: the sender paused longer than the receiver's poll
  /// timeout, the sweep in progress was handed over, and the packets after the pause went on with
  /// that revolution [count].
  std::uint64_t pause_cuts = 0;
  std::size_t queue_depth = 0;          ///< items waiting for the writer [count]
  std::size_t queue_high_water = 0;     ///< largest queue_depth so far, to size queue_capacity [count]
  double rate_pps = 0;                  ///< data packets per second over the last status period [1/s]
  double clock_offset_s = 0;            ///< host receive time - sensor time (within the hour), last packet [s]
  double clock_offset_min_s = 0, clock_offset_max_s = 0;  ///< over the session [s]
  bool silent = false;                  ///< no packet for silent_after_s
  std::uint64_t silent_events = 0;      ///< times it went silent [count]
  /// The model its packets show (velodyne/model_choice.h: "VLP-16", "HDL-32E", "unknown"; "undecided"
  /// before its first sweep), why ("ini", "packet layout", "product byte") and the layout found.
  std::string lidar_model = "undecided", lidar_model_source, lidar_layout;
};

struct CanStatus {
  bool enabled = false;
  std::uint64_t frames = 0;             ///< frames received [count]
  std::uint64_t error_frames = 0;       ///< CAN_ERR_FLAG frames [count]
  std::uint64_t bus_off = 0;            ///< error frames with CAN_ERR_BUSOFF [count]
  std::uint64_t kernel_drops = 0;       ///< SO_RXQ_OVFL / bad log lines [count]
  std::uint64_t malformed = 0;          ///< datagrams of an unexpected size [count]
  std::uint64_t queue_drops = 0;        ///< frames dropped because the writer queue was full [count]
  std::uint64_t vehicle_observations = 0;  ///< MRPT observations decoded from CAN (odometry, IMU, GPS) [count]
  std::size_t queue_depth = 0;
  std::size_t queue_high_water = 0;     ///< largest queue_depth so far [count]
  double rate_fps = 0;                  ///< frames per second over the last status period [1/s]
  bool silent = false;                  ///< no frame for CanParams::silent_after_s
  std::uint64_t silent_events = 0;      ///< times the bus went silent [count]
  std::string error;                    ///< why the CAN source stopped, if it did
};

struct GnssStatus {
  bool enabled = false;
  std::string source;                   ///< "serial:/dev/ttyACM0", "gpsd:localhost:2947", "nmea-log:..."
  std::uint64_t lines = 0;              ///< sentences received [count]
  std::uint64_t epochs = 0;             ///< valid receiver epochs (fixes) queued for the rawlog [count]
  std::uint64_t split_epochs = 0;       ///< late parts of an epoch already written (epoch_idle_ms too short) [count]
  std::uint64_t queue_drops = 0;        ///< lines / epochs dropped because the writer queue was full [count]
  gnss::NmeaCounters nmea;              ///< checksum errors, no fix, time jumps, other datums ...
  std::vector<std::string> problems;    ///< the first parsing problems, "line N: what"
  int quality = -1;                     ///< GGA quality of the last fix (-1: none yet)
  int satellites = 0;                   ///< of the last fix
  double hdop = gnss::kNaN;             ///< of the last fix
  std::size_t queue_depth = 0, queue_high_water = 0;
  bool silent = false;                  ///< no sentence for GnssParams::silent_after_s
  std::uint64_t silent_events = 0;
  std::string error;                    ///< why the GNSS source stopped, if it did
};

struct WriterStatus {
  std::uint64_t observations = 0;       ///< objects in the rawlog [count]
  std::uint64_t sweeps = 0, packets = 0;  ///< written [count]
  std::uint64_t gps = 0;                ///< CObservationGPS from the LiDARs' position packets and the GNSS receiver (CAN's: in vehicle_observations) [count]
  std::uint64_t bytes = 0;              ///< compressed rawlog bytes, all segments [bytes]
  std::size_t segments = 0;             ///< rawlog files [count]
  std::size_t pending = 0;              ///< observations held for time ordering [count]
  std::uint64_t late = 0;               ///< arrived after newer ones were written (written anyway) [count]
  std::string current_segment;
  std::string error;                    ///< first write error (disk full...): recording goes on, counted
  std::uint64_t write_errors = 0;
};

struct GrabStatus {
  double elapsed_s = 0;
  std::vector<SensorStatus> sensors;
  CanStatus can;
  GnssStatus gnss;
  WriterStatus writer;
  std::vector<std::string> events;      ///< watchdog messages since the last status() call
};

class Grabber {
 public:
  /// Validates the parameters, creates \p out_dir, opens the sockets, the CAN source and the
  /// first rawlog segment, writes the session files (params_used.ini, calibrations). Throws
  /// naming the port, interface or file on failure. Nothing is received until start().
  /// An empty \p out_dir monitors without recording: no file is written (no rawlog, sidecars or
  /// summary.json), the observations only go to the tap (roadslam-view --udp / --grab).
  Grabber(const GrabParams& params, const std::string& out_dir);
  /// Every observation written (or, monitoring, that would be) also goes to \p tap; call before
  /// start().
  void setObservationTap(ObservationTap tap);
  /// Replaces the CAN source by an open datagram socket carrying struct can_frame (socketpair
  /// tests); call before start().
  void useCanSocket(int fd, const std::string& interface_name);
  ~Grabber();  ///< stop()s
  Grabber(const Grabber&) = delete;
  Grabber& operator=(const Grabber&) = delete;

  void start();
  /// Stops the receivers, writes everything queued, closes the segments and sidecars, writes
  /// summary.json. Idempotent.
  void stop();
  /// Counters now; also runs the watchdog (events). Thread-safe.
  GrabStatus status();
  /// One human-readable line of status() (the app prints it every second).
  static std::string formatStatus(const GrabStatus& s);
  /// Writes \p out_dir/summary.json (atomically) from status(); also done by stop().
  void writeSummary(const GrabStatus& s) const;
  /// Bound data port of sensor \p i (useful with data_port = 0).
  std::uint16_t dataPort(std::size_t i) const;
  std::uint16_t positionPort(std::size_t i) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace roadslam::grabber
