// roadslam-map: LiDAR odometry (and, as it grows, the maps) over a recording.
#include <CLI/CLI.hpp>
#include <iostream>

#include "roadslam/common/cli.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/jobs/map_job.h"

int main(int argc, char** argv) {
  CLI::App app{"LiDAR odometry and mapping over a recording (.pcap, .rawlog or a KITTI .bin folder)"};
  roadslam::jobs::MapRequest req;
  bool quiet = false, json = false;
  roadslam::addVersionFlag(app, "roadslam-map");
  app.add_option("--config", req.config_path, "ini file (e.g. ini/default.ini)")->required()->check(CLI::ExistingFile);
  app.add_option("--input", req.input_path, "recording: .pcap, .rawlog or folder of KITTI .bin sweeps")->required();
  app.add_option("--out", req.out_dir, "output folder (created when missing)")->required();
  app.add_option("--times", req.times_path, "KITTI folder: its times file (default: times.txt beside or one level up)")
      ->check(CLI::ExistingFile);
  app.add_option("--max-frames", req.max_frames, "stop after this many frames (0 = all)")->check(CLI::NonNegativeNumber);
  app.add_option("--can", req.can_log_path, "candump log of the same drive: wheel odometry prior")->check(CLI::ExistingFile);
  app.add_option("--vehicle", req.vehicle_ini_path, "the car's vehicle ini (ini/vehicles/...), with --can")->check(CLI::ExistingFile);
  app.add_option("--gnss", req.gnss_path, "NMEA log of the same drive: GNSS fused at the end, geo-referenced outputs")
      ->check(CLI::ExistingFile);
  auto* from_input = app.add_flag("--gnss-from-input", req.gnss_from_input,
                                  "fuse the GPS fixes the input carries (position packets, a rawlog's GPS records) instead of --gnss");
  app.add_option("--gnss-label", req.gnss_label,
                 "with --gnss-from-input: the sensor label of the GPS source to fuse when the input has several (e.g. CAN_GPS)")
      ->needs(from_input);
  app.add_option("--prior-map", req.prior_map_dir,
                 "map folder of an earlier run: localize each sweep in it (no mapping); localization.csv per sweep")
      ->check(CLI::ExistingDirectory);
  app.add_flag("--export-sweeps", req.export_sweeps,
               "each posed sweep, deskewed (lidar frame at its reference time), as OUT/sweeps/NNNNNN.pcd");
  roadslam::addForceFlag(app, req.force);
  roadslam::addAllowUnknownKeysFlag(app, req.allow_unknown_keys);
  app.add_flag("--quiet", quiet, "nothing on stdout (no progress bar, no summary); errors and warnings on stderr");
  app.add_flag("--json", json, "print the summary as JSON (as in OUT/summary.json) instead of text");
  CLI11_PARSE(app, argc, argv);
  req.progress = !quiet;
  roadslam::installStopSignalHandlers();
  try {
    const auto out = roadslam::jobs::runMapJob(req);
    if (!quiet) std::cout << (json ? out.summary.dump(2) + "\n" : roadslam::jobs::summaryText(out.summary, req.out_dir));
    for (const auto& w : out.summary["warnings"]) std::cerr << "roadslam-map: warning: " << w.get<std::string>() << "\n";
    for (const auto& e : out.summary["write_errors"]) std::cerr << "roadslam-map: " << e.get<std::string>() << "\n";
    if (!out.summary["write_errors"].empty()) return 1;  // the other outputs are there, summary.json lists what is not
    if (out.interrupted) return roadslam::interruptedExit("roadslam-map", "the outputs of the sweeps so far are in " + req.out_dir);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "roadslam-map: " << e.what() << "\n";
    return 1;
  }
}
