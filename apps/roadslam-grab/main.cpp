// roadslam-grab: record LiDARs (UDP) and CAN into MRPT rawlog segments + sidecars.
// See docs/apps/roadslam-grab.md.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

#include "roadslam/common/cli.h"
#include "roadslam/grabber/session.h"

int main(int argc, char** argv) {
  CLI::App app{"roadslam-grab: live LiDAR + CAN recording into MRPT rawlogs"};
  roadslam::addVersionFlag(app, "roadslam-grab");
  roadslam::grabber::SessionOptions opt;
  app.add_option("--config", opt.ini_path, "grabber ini (ini/grab.ini)")->required()->check(CLI::ExistingFile);
  app.add_option("--out", opt.out_dir, "session folder")->required();
  app.add_option("--duration", opt.duration_s, "stop after S seconds (default: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  bool quiet = false;
  app.add_flag("--quiet", quiet, "nothing on stdout (no final status, no summary path); status and errors on stderr");
  CLI11_PARSE(app, argc, argv);
  try {
    const auto params = roadslam::grabber::GrabParams::fromFile(opt.ini_path);
    const auto st = roadslam::grabber::runSession(params, opt, [](const std::string& line) {
      std::fprintf(stderr, "%s\n", line.c_str());
    });
    if (!quiet) {
      std::printf("%s\n", roadslam::grabber::Grabber::formatStatus(st).c_str());
      std::printf("summary: %s/summary.json\n", opt.out_dir.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roadslam-grab: %s\n", e.what());
    return 1;
  }
  return 0;
}
