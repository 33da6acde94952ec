// roadslam-sim: simulate a scenario into DIR/velodyne.pcap (or, for [lidar] model = hdl64, a KITTI raw-style
// DIR/velodyne/*.bin folder) + DIR/can.log + ground truth, optionally streaming the data packets over UDP.
// See docs/apps/roadslam-sim.md.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

#include "roadslam/common/cli.h"
#include "roadslam/sim/outputs.h"
#include "roadslam/sim/simulator.h"

int main(int argc, char** argv) {
  CLI::App app{"roadslam-sim: packet-level VLP-16 / KITTI-style HDL-64E simulator with ground truth"};
  roadslam::addVersionFlag(app, "roadslam-sim");
  std::string scenario, out, udp, top_view;
  unsigned long long seed = 0;
  double duration = 0, speed = 1.0;
  bool quiet = false;
  app.add_option("--scenario", scenario, "scenario ini (ini/sim/*.ini)")->required()->check(CLI::ExistingFile);
  app.add_option("--out", out, "output folder")->required();
  auto* seed_opt = app.add_option("--seed", seed, "override [scenario] seed (>= 0)")->check(CLI::Range(0, 2147483647));
  auto* duration_opt = app.add_option("--duration", duration, "override [scenario] duration_s [s] (0 = whole drive)")
                           ->check(CLI::Range(0.0, 1e6));
  app.add_option("--udp", udp, "also stream the data packets to HOST:PORT (IPv4)");
  app.add_option("--speed", speed, "UDP pace as a multiple of real time (> 0)")->check(CLI::PositiveNumber);
  app.add_option("--top-view", top_view, "draw a top view of the world to this PNG");
  app.add_flag("--quiet", quiet, "nothing on stdout (no summary) and no progress bar; errors on stderr");
  CLI11_PARSE(app, argc, argv);
  try {
    auto params = roadslam::sim::ScenarioParams::fromFile(scenario);
    if (seed_opt->count() > 0) params.seed = seed;
    if (duration_opt->count() > 0) params.duration_s = duration;
    roadslam::sim::OutputOptions opt;
    opt.dir = out;
    opt.top_view_png = top_view;
    opt.progress = !quiet;
    if (!udp.empty()) {
      const auto colon = udp.rfind(':');
      const int port = colon == std::string::npos ? 0 : std::atoi(udp.c_str() + colon + 1);
      if (port <= 0 || port > 65535) throw std::runtime_error("--udp must be HOST:PORT, got '" + udp + "'");
      opt.udp_host = udp.substr(0, colon);
      opt.udp_port = static_cast<uint16_t>(port);
      opt.udp_speed = speed;
    }
    roadslam::sim::Simulator sim(params);
    const auto rep = roadslam::sim::runToDirectory(sim, opt);
    const auto& s = rep.stats;
    if (quiet) return 0;
    if (params.lidar.hdl64())
      std::printf("%s seed %llu: %.1f s, hdl64, %llu sweeps in %s/velodyne, %llu points, %.1f m, %.1fx real time\n",
                  params.name.c_str(), static_cast<unsigned long long>(params.seed), s.duration_s,
                  static_cast<unsigned long long>(s.sweeps), out.c_str(),
                  static_cast<unsigned long long>(s.lidar.returns), s.distance_m, rep.real_time_factor);
    else
      std::printf("%s seed %llu: %.1f s, %llu packets, %llu sweeps, %llu points, %.1f m, %.1fx real time%s\n",
                  params.name.c_str(), static_cast<unsigned long long>(params.seed), s.duration_s,
                  static_cast<unsigned long long>(s.data_packets), static_cast<unsigned long long>(s.sweeps),
                  static_cast<unsigned long long>(s.lidar.returns), s.distance_m, rep.real_time_factor,
                  udp.empty() ? "" : (", " + std::to_string(rep.packets_sent) + " packets sent").c_str());
    if (rep.can_frames > 0) std::printf("can.log: %zu CAN frames, DBC %s\n", rep.can_frames, rep.can_dbc.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roadslam-sim: %s\n", e.what());
    return 1;
  }
  return 0;
}
