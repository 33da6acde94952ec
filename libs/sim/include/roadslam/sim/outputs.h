#pragma once
/// \file outputs.h
/// Running a scenario into an output folder (all files written atomically):
///   velodyne.pcap       data packets (port 2368) and $GPRMC position packets (port 8308)
///                       ([lidar] model = vlp16), or with model = hdl64 a KITTI raw-style folder:
///   velodyne/NNNNNN.bin float32 x, y, z, reflectance [0..1] per point, firing order, each sweep
///                       from azimuth 180 deg (behind) clockwise round to 180 deg
///   times.txt           one stamp per sweep, the moment it fires forward (azimuth 0, mid-sweep),
///                       on the capture clock [s since epoch, %.6f]
///   poses_velo_kitti.txt  T_lidar0_lidar at each stamp, KITTI 3x4 row-major (lidar0: first sweep)
///   gt_trajectory.tum   T_world_lidar every 10 ms, "t x y z qx qy qz qw", t on the capture clock
///   gt_vehicle.csv      vehicle reference state every 10 ms: pose, speed, acceleration, yaw rate,
///                       rear wheel speeds, distance (header line names the columns and units)
///   gt_boundaries.json  per road: centreline and left/right curb polylines [x, y, z] (world frame)
///   gt_objects.json     moving cars' tracks at 10 Hz [t, x, y, z, yaw, returns, range_m]: returns =
///                       lidar points on the car fired within 0.05 s of t (its visibility; 0 when
///                       hidden), range_m = x-y distance from the lidar to the car's centre
///   can.log             the car's CAN traffic in candump -l format (can_output.h), same clock
///   gnss.nmea, gt_gnss.csv  with [gnss] enabled: the receiver's NMEA log and its truth (gnss_output.h)
///   summary.json        scenario, seed, duration_s, packets, sweeps, points, distance_m,
///                       real_time_factor (packets_sent with UDP), can_frames and can_dbc
///   scenario_used.ini   the parameters actually used
/// and, optionally, UDP streaming of the data packets paced at a multiple of real time.

#include <cstdint>
#include <string>

#include "roadslam/sim/simulator.h"

namespace roadslam::sim {

struct OutputOptions {
  std::string dir;               ///< output folder (created when missing)
  std::string udp_host;          ///< IPv4 address to stream the data packets to; empty = no UDP
  uint16_t udp_port = 0;         ///< [-]
  double udp_speed = 1.0;        ///< pace: 1 = real time, 2 = twice as fast [-]
  std::string top_view_png;      ///< also draw the top view here when not empty
  /// Progress on stderr when it is a terminal: simulated seconds of the scenario's, with ETA
  bool progress = false;
};

struct RunReport {
  SimStats stats;
  uint64_t packets_sent = 0;     ///< UDP datagrams sent (data packets)
  uint64_t packets_late = 0;     ///< UDP datagrams sent behind their pace time by > 10 ms
  double real_time_factor = 0;   ///< simulated seconds per wall-clock second (whole run) [-]
  std::size_t can_frames = 0;    ///< frames written to can.log (0 when [can] enabled = false)
  std::string can_dbc;           ///< DBC the CAN traffic was encoded with (empty without CAN)
  GnssRun gnss;                  ///< [gnss] enabled: epochs written
};

/// Simulates \p sim into \p opt.dir (and UDP); throws naming the file on I/O errors.
RunReport runToDirectory(Simulator& sim, const OutputOptions& opt);

/// Simulates \p p into \p dir (runToDirectory, no UDP) unless a finished run is there; returns \p dir.
/// For tests that share one drive per build tree: the run is written beside (dir.tmp<pid>), marked
/// finished (dir/.complete) and renamed into place, so a run interrupted part way never leaves a
/// half-written folder in use. The marker holds \p p as saved (ScenarioParams::saveToConfigFile): a
/// folder simulated from other parameters is simulated again. Test processes running in parallel
/// take turns on the lock file dir.lock (flock), so a drive two of them want at once is simulated
/// once: the second waits for the first and reuses its folder. \p simulated (when given) tells which.
std::string simulateOnce(const ScenarioParams& p, const std::string& dir, bool* simulated = nullptr);

/// The folder of \p p's drive in a cache of drives: \p cache_dir/<name>-<duration>-<hash>, the hash
/// (FNV-1a, 64 bits) of \p p as saved, so every scenario has a folder of its own whoever asks for it.
std::string cachedDriveDir(const ScenarioParams& p, const std::string& cache_dir);

/// simulateOnce(p, cachedDriveDir(p, cache_dir)): the tests' drives, one cache per build tree
/// (ROADSLAM_SIM_CACHE, <build>/sim-cache) shared by every test binary.
std::string simulateCached(const ScenarioParams& p, const std::string& cache_dir, bool* simulated = nullptr);

/// Top view: world primitives, roads, curbs (green), route (red), start (circle) to a PNG.
void drawTopView(const Simulator& sim, const std::string& png_path, int max_px = 1600);

/// Sends UDP payloads paced on their capture times (divided by \p speed). Throws naming the
/// address when the socket cannot be created.
class UdpStreamer : public PacketSink {
 public:
  UdpStreamer(const std::string& host, uint16_t port, double speed);
  ~UdpStreamer() override;
  UdpStreamer(const UdpStreamer&) = delete;
  UdpStreamer& operator=(const UdpStreamer&) = delete;
  /// Data packets (port 2368) go to host:port; position packets are not streamed.
  void packet(double capture_s, uint16_t port, const uint8_t* data, std::size_t size) override;
  uint64_t sent() const { return sent_; }
  uint64_t late() const { return late_; }

 private:
  int fd_ = -1;
  uint8_t addr_[16]{};  ///< sockaddr_in
  double speed_;
  double first_capture_ = -1;
  double wall0_ = 0;
  uint64_t sent_ = 0, late_ = 0;
};

}  // namespace roadslam::sim
