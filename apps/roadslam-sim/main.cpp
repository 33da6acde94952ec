// roadslam-sim: simulate a scenario into DIR/velodyne.pcap (or, for [lidar] model = hdl64, a KITTI raw-style
// DIR/velodyne/*.bin folder) + DIR/can.log + ground truth, optionally streaming the data packets over UDP.
// See docs/apps/roadslam-sim.md.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

#include "roadslam/common/cli.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/jobs/sim_job.h"

int main(int argc, char** argv) {
  CLI::App app{"roadslam-sim: packet-level VLP-16 / KITTI-style HDL-64E simulator with ground truth"};
  roadslam::addVersionFlag(app, "roadslam-sim");
  roadslam::jobs::SimRequest req;
  unsigned long long seed = 0;
  double duration = 0;
  bool quiet = false;
  app.add_option("--config,--scenario", req.scenario_path, "scenario ini (ini/sim/*.ini)")->required()->check(CLI::ExistingFile);
  app.add_option("--out", req.out_dir, "output folder (new, empty, or an earlier run of the same scenario)")->required();
  auto* seed_opt = app.add_option("--seed", seed, "override [scenario] seed (>= 0)")->check(CLI::Range(0, 2147483647));
  auto* duration_opt = app.add_option("--duration", duration, "override [scenario] duration_s [s] (0 = whole drive)")
                           ->check(CLI::Range(0.0, 1e6));
  app.add_option("--udp", req.udp, "also stream the data packets to HOST:PORT (IPv4)");
  app.add_option("--speed", req.udp_speed, "UDP pace as a multiple of real time (> 0)")->check(CLI::PositiveNumber);
  app.add_option("--top-view", req.top_view_png, "draw a top view of the world to this PNG");
  roadslam::addForceFlag(app, req.force);
  roadslam::addAllowUnknownKeysFlag(app, req.allow_unknown_keys);
  app.add_flag("--quiet", quiet, "nothing on stdout (no summary) and no progress bar; errors on stderr");
  roadslam::warnOldSpellings(argc, argv, "roadslam-sim", {{"--scenario", "--config"}});
  CLI11_PARSE(app, argc, argv);
  req.progress = !quiet;
  if (seed_opt->count() > 0) req.seed = seed;
  if (duration_opt->count() > 0) req.duration_s = duration;
  roadslam::installStopSignalHandlers();
  try {
    const auto out = roadslam::jobs::runSimJob(req);
    for (const auto& w : out.warnings) std::fprintf(stderr, "roadslam-sim: warning: %s\n", w.c_str());
    if (!quiet) std::fputs(roadslam::jobs::simSummaryText(out, req).c_str(), stdout);
    if (out.report.stats.interrupted) {
      char what[64];
      std::snprintf(what, sizeof what, "the first %.1f s of the drive are in ", out.report.stats.duration_s);
      return roadslam::interruptedExit("roadslam-sim", what + req.out_dir);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roadslam-sim: %s\n", e.what());
    return 1;
  }
  return 0;
}
