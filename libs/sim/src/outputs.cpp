#include "roadslam/sim/outputs.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <nlohmann/json.hpp>

#include "roadslam/can/candump.h"
#include "roadslam/common/atomic_file.h"
#include "roadslam/common/progress.h"
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/pcap/pcap_writer.h"
#include "roadslam/sim/eigen.h"

namespace roadslam::sim {

namespace {
using nlohmann::json;

class PcapSink : public PacketSink {
 public:
  /// \p progress (optional): fed the simulated seconds since the first packet.
  PcapSink(const std::string& path, PacketSink* also, ProgressBar* progress = nullptr)
      : tmp_(path), w_(tmp_.path(), path), also_(also), progress_(progress) {}
  void packet(double capture_s, uint16_t port, const uint8_t* data, std::size_t size) override {
    w_.writeUdp(capture_s, port, port, data, size);
    if (also_) also_->packet(capture_s, port, data, size);
    if (!progress_) return;
    if (!t0_) t0_ = capture_s;
    progress_->update(capture_s - *t0_, 0);
  }
  void commit() {
    w_.close();
    tmp_.commit();
  }

 private:
  TempFile tmp_;  // removed when the run throws before commit
  pcap::PcapWriter w_;
  PacketSink* also_;
  ProgressBar* progress_;
  std::optional<double> t0_;  // capture time of the first packet [s]
};

void writeTum(const Simulator& sim, double duration_s, const std::string& path) {
  AtomicFile f(path);
  const double t0 = static_cast<double>(sim.params().start_epoch_s);
  const auto n = static_cast<std::size_t>(std::floor(duration_s / Trajectory::kStep_s + 1e-9));
  char line[200];
  for (std::size_t i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) * Trajectory::kStep_s;
    const Pose3 T = sim.lidar().lidarPose(t);
    const auto q = T.quaternion();
    std::snprintf(line, sizeof(line), "%.6f %.6f %.6f %.6f %.9f %.9f %.9f %.9f\n", t0 + t, T.t.x, T.t.y,
                  T.t.z, q[0], q[1], q[2], q[3]);
    f.stream() << line;
  }
  f.commit();
}

/// Vehicle states every 10 ms (the future CAN simulation and wheel-odometry tests read these).
void writeVehicleCsv(const Simulator& sim, double duration_s, const std::string& path) {
  AtomicFile f(path);
  f.stream() << "t,x,y,z,yaw_rad,pitch_rad,roll_rad,speed_mps,accel_mps2,yaw_rate_rps,"
                "wheel_left_mps,wheel_right_mps,distance_m\n";
  const double t0 = static_cast<double>(sim.params().start_epoch_s);
  char line[320];
  for (const VehicleState& s : sim.trajectory().states()) {
    if (s.t_s > duration_s + 1e-9) break;
    std::snprintf(line, sizeof(line), "%.6f,%.4f,%.4f,%.4f,%.6f,%.6f,%.6f,%.4f,%.4f,%.6f,%.4f,%.4f,%.3f\n",
                  t0 + s.t_s, s.x, s.y, s.z, s.yaw, s.pitch, s.roll, s.speed_mps, s.accel_mps2,
                  s.yaw_rate_rps, s.wheel_speed_left_mps, s.wheel_speed_right_mps, s.s_m);
    f.stream() << line;
  }
  f.commit();
}

json polyline3(const World& w, const std::vector<Vec2>& line, std::size_t stride = 1) {
  json a = json::array();
  auto r3 = [](double v) { return std::round(v * 1000.0) / 1000.0; };
  for (std::size_t i = 0; i < line.size(); i += stride)
    a.push_back({r3(line[i].x), r3(line[i].y), r3(w.ground.height(line[i].x, line[i].y))});
  return a;
}

void writeBoundaries(const Simulator& sim, const std::string& path) {
  const World& w = sim.world();
  json roads = json::array();
  for (const Road& r : w.roads) {
    json left = json::array(), right = json::array();
    for (const auto& c : r.left_curbs) left.push_back(polyline3(w, c));
    for (const auto& c : r.right_curbs) right.push_back(polyline3(w, c));
    roads.push_back({{"name", r.name}, {"half_width_m", r.half_width_m}, {"closed", r.closed},
                     {"centerline", polyline3(w, r.centerline, 4)}, {"left_curbs", left},
                     {"right_curbs", right}});
  }
  const json j = {{"frame", "world (x east, y north, z up) [m]"},
                  {"curb_height_m", sim.params().world.curb_height_m},
                  {"note", "left/right of the centreline direction; curb polylines run along the curb face"},
                  {"roads", roads}};
  writeFileAtomically(path, j.dump(1) + "\n");
}

void writeObjects(const Simulator& sim, double duration_s, const std::string& path) {
  const World& w = sim.world();
  json cars = json::array();
  const double t0 = static_cast<double>(sim.params().start_epoch_s);
  for (std::size_t i = 0; i < w.cars.size(); ++i) {
    const MovingCar& c = w.cars[i];
    json track = json::array();
    const auto& returns = sim.lidar().carReturns()[i];
    std::size_t k = 0;
    for (double t = 0; t <= duration_s + 1e-9; t += 0.1, ++k) {  // t accumulates as before (same stamps)
      const CarPose p = w.carPose(c, t);
      const Pose3 T_world_lidar = sim.lidar().lidarPose(t);
      const double range = std::hypot(p.x - T_world_lidar.t.x, p.y - T_world_lidar.t.y);
      // returns: points on the car fired within 0.05 s of t (LidarSimulator::carReturns)
      track.push_back({t0 + t, p.x, p.y, p.z, p.yaw, k < returns.size() ? returns[k] : 0u, range});
    }
    cars.push_back({{"id", i}, {"road", w.roads[static_cast<std::size_t>(c.road)].name},
                    {"length_m", c.length_m}, {"width_m", c.width_m}, {"height_m", c.height_m},
                    {"speed_mps", std::abs(c.speed_mps)}, {"track", track}});
  }
  const json j = {{"frame", "world"}, {"track_fields", {"t", "x", "y", "z_ground", "yaw_rad", "returns", "range_m"}},
                  {"note", "returns: lidar points on the car fired within 0.05 s of t (0: hidden or out of range); "
                           "range_m: x-y distance from the lidar (GT pose) to the car's centre"},
                  {"moving_cars", cars},
                  {"static", {{"prisms", w.prisms.size()}, {"cylinders", w.cylinders.size()},
                              {"spheres", w.spheres.size()}}}};
  writeFileAtomically(path, j.dump() + "\n");
}
/// hdl64: the KITTI raw-style folder: velodyne/NNNNNN.bin, times.txt, poses_velo_kitti.txt.
SimStats writeKittiFolder(Simulator& sim, const std::string& d, ProgressBar* progress) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(d + "velodyne", ec);
  if (!fs::is_directory(d + "velodyne")) throw std::runtime_error("cannot create folder " + d + "velodyne");
  std::string times;
  datasets::PoseList poses;
  Eigen::Isometry3d T_first_world = Eigen::Isometry3d::Identity();
  const auto& lidar = sim.lidar();
  const SimStats st = sim.runSweeps([&](uint64_t k, Scan&& scan) {
    char name[32];
    std::snprintf(name, sizeof(name), "velodyne/%06llu.bin", static_cast<unsigned long long>(k));
    datasets::writeKittiBin(d + name, scan);
    // %.6f: the epoch clock to the microsecond (as datasets::writeTimes, which writes 9 decimals).
    char line[64];
    std::snprintf(line, sizeof(line), "%.6f\n", scan.stamp_s);
    times += line;
    const Eigen::Isometry3d T_world_lidar = toEigen(lidar.lidarPose(lidar.sweepStamp_s(k)));
    if (k == 0) T_first_world = T_world_lidar.inverse();
    poses.push_back(T_first_world * T_world_lidar);
    if (progress) progress->update(lidar.sweepStamp_s(k) - lidar.sweepStamp_s(0), static_cast<size_t>(k + 1));
  });
  writeFileAtomically(d + "times.txt", times);
  datasets::writeKittiPoses(d + "poses_velo_kitti.txt", poses);
  return st;
}
}  // namespace

RunReport runToDirectory(Simulator& sim, const OutputOptions& opt) {
  namespace fs = std::filesystem;
  const auto wall0 = std::chrono::steady_clock::now();
  std::error_code ec;
  fs::create_directories(opt.dir, ec);
  if (!fs::is_directory(opt.dir)) throw std::runtime_error("cannot create output folder " + opt.dir);
  const std::string d = opt.dir + "/";
  std::unique_ptr<UdpStreamer> udp;
  if (!opt.udp_host.empty()) udp = std::make_unique<UdpStreamer>(opt.udp_host, opt.udp_port, opt.udp_speed);
  RunReport rep;
  std::optional<ProgressBar> bar;
  if (opt.progress) bar.emplace("roadslam-sim", sim.duration_s(), ProgressMeasure::SimulatedSeconds);
  ProgressBar* progress = bar ? &*bar : nullptr;
  if (sim.params().lidar.hdl64()) {
    if (udp) throw std::runtime_error("--udp needs [lidar] model = vlp16 (hdl64 writes a .bin folder)");
    rep.stats = writeKittiFolder(sim, d, progress);
  } else {
    PcapSink pcap(d + "velodyne.pcap", udp.get(), progress);
    rep.stats = sim.run(pcap);
    pcap.commit();
  }
  if (bar) bar->finish();
  writeTum(sim, rep.stats.duration_s, d + "gt_trajectory.tum");
  writeVehicleCsv(sim, rep.stats.duration_s, d + "gt_vehicle.csv");
  writeBoundaries(sim, d + "gt_boundaries.json");
  writeObjects(sim, rep.stats.duration_s, d + "gt_objects.json");
  if (sim.params().can.enabled) {
    const auto frames = simulateCan(sim, rep.stats.duration_s);
    can::writeCandumpFile(d + "can.log", frames);
    rep.can_frames = frames.size();
    rep.can_dbc = sim.params().can.dbcPath();
  }
  if (sim.params().gnss.enabled) rep.gnss = writeGnss(sim, rep.stats.duration_s, d);
  mrpt::config::CConfigFileMemory used;
  sim.params().saveToConfigFile(used);
  writeFileAtomically(d + "scenario_used.ini", used.getContent());
  if (!opt.top_view_png.empty()) drawTopView(sim, opt.top_view_png);
  if (udp) {
    rep.packets_sent = udp->sent();
    rep.packets_late = udp->late();
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  rep.real_time_factor = rep.stats.duration_s / std::max(1e-9, wall);
  const auto& s = rep.stats;
  json j = {{"scenario", sim.params().name}, {"seed", sim.params().seed}, {"duration_s", s.duration_s},
            {"packets", s.data_packets}, {"position_packets", s.position_packets}, {"sweeps", s.sweeps},
            {"points", s.lidar.returns}, {"rays", s.lidar.rays}, {"distance_m", s.distance_m},
            {"real_time_factor", rep.real_time_factor},
            {"simulation_real_time_factor", s.duration_s / std::max(1e-9, s.wall_s)},
            {"lost_returns", {{"no_hit", s.lidar.no_hit}, {"too_close", s.lidar.too_close},
                              {"grazing", s.lidar.grazing}, {"dark", s.lidar.dark},
                              {"dropped", s.lidar.dropped}}},
            {"start_epoch_s", sim.params().start_epoch_s}, {"lidar_model", sim.params().lidar.model},
            {"interrupted", s.interrupted}, {"complete", !s.interrupted}};
  if (sim.params().can.enabled) {
    j["can_frames"] = rep.can_frames;
    j["can_dbc"] = rep.can_dbc;
  }
  if (sim.params().gnss.enabled) {
    j["gnss"] = {{"epochs", rep.gnss.epochs}, {"fixes", rep.gnss.fixes}, {"outage_epochs", rep.gnss.outage_epochs},
                 {"multipath_epochs", rep.gnss.multipath_epochs}};
  }
  if (udp) {
    j["packets_sent"] = rep.packets_sent;
    j["packets_late"] = rep.packets_late;
    j["udp_speed"] = opt.udp_speed;
  }
  writeFileAtomically(d + "summary.json", j.dump(1) + "\n");
  return rep;
}

namespace {

std::string savedScenario(const ScenarioParams& p) {
  mrpt::config::CConfigFileMemory used;
  p.saveToConfigFile(used);
  return used.getContent();
}

/// An exclusive flock on a file, held until destroyed (or the process ends: a killed test frees it).
class FileLock {
 public:
  explicit FileLock(const std::string& path) : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644)) {
    if (fd_ < 0) throw std::runtime_error("cannot open lock file " + path);
    while (::flock(fd_, LOCK_EX) != 0) {
      if (errno != EINTR) {
        ::close(fd_);
        throw std::runtime_error("cannot lock " + path);
      }
    }
  }
  ~FileLock() { ::close(fd_); }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

 private:
  int fd_;
};

}  // namespace

std::string simulateOnce(const ScenarioParams& p, const std::string& dir, bool* simulated) {
  namespace fs = std::filesystem;
  if (simulated) *simulated = false;
  // the marker holds the scenario the folder was simulated from: a changed scenario ini (or a
  // default) under the same name simulates again instead of reusing the old drive
  const std::string scenario = savedScenario(p);
  const auto readMarker = [&] {
    std::ifstream f(dir + "/.complete", std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  };
  std::error_code ec;
  const fs::path parent = fs::path(dir).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  const FileLock lock(dir + ".lock");  // a process simulating this drive finishes before we look
  if (fs::exists(dir + "/.complete")) {
    if (readMarker() == scenario) return dir;
    std::fprintf(stderr, "simulateOnce: %s was simulated from another scenario: simulating it again\n", dir.c_str());
  }
  const std::string tmp = dir + ".tmp" + std::to_string(::getpid());
  fs::remove_all(tmp, ec);
  Simulator s(p);
  OutputOptions o;
  o.dir = tmp;
  runToDirectory(s, o);
  writeFileAtomically(tmp + "/.complete", scenario);
  fs::remove_all(dir, ec);  // unfinished, or of another scenario (under the lock: no one else uses it)
  fs::rename(tmp, dir, ec);
  if (ec) throw std::runtime_error("cannot rename " + tmp + " to " + dir + ": " + ec.message());
  if (simulated) *simulated = true;
  return dir;
}

std::string cachedDriveDir(const ScenarioParams& p, const std::string& cache_dir) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a: stable across runs and compilers (std::hash is not)
  for (const unsigned char c : savedScenario(p)) h = (h ^ c) * 1099511628211ull;
  std::string name;
  for (const char c : p.name) name += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  char tail[64];
  if (p.duration_s > 0) {
    std::snprintf(tail, sizeof(tail), "-%gs-%016llx", p.duration_s, static_cast<unsigned long long>(h));
  } else {
    std::snprintf(tail, sizeof(tail), "-full-%016llx", static_cast<unsigned long long>(h));
  }
  return cache_dir + "/" + name + tail;
}

std::string simulateCached(const ScenarioParams& p, const std::string& cache_dir, bool* simulated) {
  return simulateOnce(p, cachedDriveDir(p, cache_dir), simulated);
}

}  // namespace roadslam::sim
