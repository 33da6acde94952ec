// roadslam-bounds: road boundaries, obstacles and free space over a recording.
#include <CLI/CLI.hpp>
#include <iostream>

#include "roadslam/jobs/bounds_job.h"
#include "roadslam/common/cli.h"
#include "roadslam/common/stop_signal.h"

int main(int argc, char** argv) {
  CLI::App app{"Road boundaries (curbs), obstacles, free space and a cost grid per sweep"};
  roadslam::jobs::BoundsRequest req;
  bool quiet = false, json = false;
  roadslam::addVersionFlag(app, "roadslam-bounds");
  app.add_option("--config", req.config_path, "ini file (e.g. ini/bounds.ini)")->required()->check(CLI::ExistingFile);
  app.add_option("--input", req.input_path, "recording: .pcap, .rawlog or folder of KITTI .bin sweeps")->required();
  app.add_option("--out", req.out_dir, "output folder (created when missing)")->required();
  app.add_option("--trajectory", req.trajectory_path, "TUM poses T_map_lidar (else the odometry runs)")
      ->check(CLI::ExistingFile);
  app.add_option("--times", req.times_path, "KITTI folder: its times file (default: times.txt beside or one level up)")
      ->check(CLI::ExistingFile);
  app.add_option("--georef", req.georef_path,
                 "map_georef.json of roadslam-map --gnss: also write boundaries.geojson / .kml (poses: that run's trajectory.tum)")
      ->check(CLI::ExistingFile);
  app.add_option("--png-every", req.png_every, "draw every N-th sweep into OUT/frames (0 = none)");
  app.add_option("--max-frames", req.max_frames, "stop after this many sweeps (0 = all)")->check(CLI::NonNegativeNumber);
  app.add_flag("--whole-drive", req.whole_drive,
               "two passes: fit every sweep from the curbs of the whole drive, along its own path "
               "(a finished drive; default: live, each sweep from the sweeps before it)");
  roadslam::addForceFlag(app, req.force);
  roadslam::addAllowUnknownKeysFlag(app, req.allow_unknown_keys);
  app.add_flag("--quiet", quiet, "nothing on stdout (no progress bar, no summary); errors on stderr");
  app.add_flag("--json", json, "print the summary as JSON (as in OUT/summary.json) instead of text");
  CLI11_PARSE(app, argc, argv);
  req.progress = !quiet;
  roadslam::installStopSignalHandlers();
  try {
    const auto summary = roadslam::jobs::runBoundsJob(req);
    if (!quiet) std::cout << (json ? summary.dump(2) + "\n" : roadslam::jobs::boundsSummaryText(summary, req.out_dir));
    for (const auto& w : summary["warnings"]) std::cerr << "roadslam-bounds: warning: " << w.get<std::string>() << "\n";
    if (summary.value("interrupted", false))
      return roadslam::interruptedExit("roadslam-bounds", "the outputs of the sweeps so far are in " + req.out_dir);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "roadslam-bounds: " << e.what() << "\n";
    return 1;
  }
}
