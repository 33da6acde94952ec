#pragma once
/// \file simulator.h
/// A scenario (world + route + drive + sensor) simulated into real VLP-16 UDP payloads.
/// Clock: simulation time t = 0 is capture time ScenarioParams::start_epoch_s; a data packet's
/// timestamp field is the time of its first firing in microseconds past the hour, and its capture
/// time is that of its last firing (first firing + 1.327104 ms), when a real sensor sends it.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "roadslam/sim/can_output.h"
#include "roadslam/sim/gnss_output.h"
#include "roadslam/sim/lidar.h"
#include "roadslam/sim/trajectory.h"
#include "roadslam/sim/world.h"
#include "roadslam/sim/world_builder.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::sim {

/// Everything a scenario ini holds: sections [scenario], [world], [trajectory], [lidar], [can], [gnss].
struct ScenarioParams {
  std::string name = "unnamed";
  uint64_t seed = 1;                 ///< world and noise seed [-]
  double duration_s = 0;             ///< 0 = the whole drive [s]
  int64_t start_epoch_s = 1700000000;  ///< capture time of t = 0 [s since the Unix epoch, UTC]
  bool position_packets = true;      ///< $GPRMC position packets at 1 Hz on port 8308
  double origin_lat_deg = 48.137, origin_lon_deg = 11.575;  ///< world origin for $GPRMC [deg]
  WorldParams world;
  TrajectoryParams trajectory;
  LidarParams lidar;
  CanParams can;
  GnssParams gnss;  ///< [gnss]: saved only when enabled (scenario_used.ini unchanged without it)

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Loads every section; throws naming the file, section and key on a bad value or an unknown key.
  /// Unknown sections and keys throw naming file, line and the nearest known key; with \p unknown
  /// (--allow-unknown-keys) unknown keys are appended there as warnings instead.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, std::vector<std::string>* unknown = nullptr);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const;
  /// loadIniFile() + loadFromConfigFile(), errors prefixed with \p path.
  static ScenarioParams fromFile(const std::string& path, std::vector<std::string>* unknown = nullptr);
};

/// Receives the simulated UDP payloads in time order.
class PacketSink {
 public:
  virtual ~PacketSink() = default;
  /// \p capture_s: capture time [s since epoch]; \p port: UDP destination port.
  virtual void packet(double capture_s, uint16_t port, const uint8_t* data, std::size_t size) = 0;
};

struct SimStats {
  uint64_t data_packets = 0, position_packets = 0, sweeps = 0;
  double duration_s = 0, distance_m = 0;  ///< simulated time [s], distance driven [m]
  double wall_s = 0;                      ///< wall-clock time of run() [s]
  LidarCounters lidar;
  /// A stop signal (stop_signal.h) ended the run early: duration_s is what was simulated.
  bool interrupted = false;
};

class Simulator {
 public:
  explicit Simulator(const ScenarioParams& params);
  ~Simulator();
  // The trajectory and the lidar model refer to world_: neither copyable nor movable.
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;
  const ScenarioParams& params() const { return p_; }
  const World& world() const { return world_; }
  const Road& route() const { return route_; }
  const Trajectory& trajectory() const { return *trajectory_; }
  const LidarSimulator& lidar() const { return *lidar_; }
  /// Simulated duration: params.duration_s, or the whole drive when 0 [s].
  double duration_s() const;
  /// Data packet timestamp field for packet \p k [us past the hour].
  uint32_t packetTimestampUs(uint64_t k) const;
  /// Capture time of data packet \p k [s since epoch].
  double packetCaptureTime(uint64_t k) const;

  /// Simulates [0, duration_s()) into \p sink; appends true returns to \p truth when given.
  /// vlp16 only (throws for hdl64).
  SimStats run(PacketSink& sink, std::vector<TrueReturn>* truth = nullptr);
  /// hdl64 only (throws for vlp16): simulates every whole sweep within [0, duration_s()) and hands
  /// each on with its index; Scan::stamp_s is its forward-facing moment on the capture clock [s
  /// since epoch] (LidarSimulator::simulateSweep).
  SimStats runSweeps(const std::function<void(uint64_t k, Scan&& scan)>& on_sweep,
                     std::vector<TrueReturn>* truth = nullptr);

 private:
  ScenarioParams p_;
  World world_;
  Road route_;
  std::unique_ptr<Trajectory> trajectory_;
  std::unique_ptr<LidarSimulator> lidar_;
};

/// A $GPRMC sentence (with checksum, no CR/LF) for the vehicle state at capture time \p epoch_s.
std::string gprmcSentence(const ScenarioParams& p, const VehicleState& s, double epoch_s);

}  // namespace roadslam::sim
