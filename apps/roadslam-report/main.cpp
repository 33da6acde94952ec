// roadslam-report: the recording report of a drive (sensors, rates, gaps and drops over time, CAN rates
// and signals, dead-reckoned path, map pictures) as DIR/report.html and DIR/report.json.
// See docs/apps/roadslam-report.md.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "roadslam/common/cli.h"
#include "roadslam/recording_report/recording_report.h"

namespace rr = roadslam::recording_report;

int main(int argc, char** argv) {
  CLI::App app{"roadslam-report: one offline HTML page (and JSON) on a recording's sensors, CAN bus and map"};
  roadslam::addVersionFlag(app, "roadslam-report");
  rr::ReportInputs in;
  rr::ReportParams p;
  std::string out;
  bool quiet = false;
  app.add_option("recording,--input", in.recording, ".pcap, .rawlog(.gz) or a roadslam-grab session folder")->required();
  app.add_option("--out", out, "output folder for report.html and report.json")->required();
  app.add_option("--can", in.can_log, "candump log (default: a grab folder's can_*.candump.log)")->check(CLI::ExistingFile);
  app.add_option("--vehicle", in.vehicle_ini, "vehicle ini (ini/vehicles/X.ini): DBC names, signals, dead reckoning")
      ->check(CLI::ExistingFile);
  app.add_option("--map", in.map_dir, "roadslam-map output folder: trajectory and map pictures");
  app.add_option("--lidar-model", in.lidar_model, "force the LiDAR model when the packets' product byte lies")
      ->check(CLI::IsMember({"vlp16", "hdl32"}));
  app.add_option("--gap-factor", p.gap_factor, "an interval over this many nominal periods is a gap")
      ->check(CLI::Range(1.0, 1e6));
  app.add_option("--min-gap", p.min_gap_s, "shorter intervals are never gaps [s]")->check(CLI::Range(0.0, 1e6));
  app.add_flag("--quiet", quiet, "print nothing but errors and warnings");
  bool force = false;
  roadslam::addForceFlag(app, force);
  CLI11_PARSE(app, argc, argv);
  try {
    if (const std::string why = rr::reportFolderRefusal(out, in); !why.empty() && !force) throw std::runtime_error(why);
    const rr::RecordingReport r = rr::buildReport(in, p);
    for (const auto& w : rr::claimReportFolder(out, in, force)) std::fprintf(stderr, "roadslam-report: warning: %s\n", w.c_str());
    rr::writeReport(r, out);
    for (const auto& w : r.warnings) std::fprintf(stderr, "roadslam-report: warning: %s\n", w.c_str());
    if (!r.damage.empty()) std::fprintf(stderr, "roadslam-report: warning: %s; reported up to there\n", r.damage.c_str());
    if (!quiet) std::printf("%s%s/report.html, %s/report.json\n", rr::toText(r).c_str(), out.c_str(), out.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "roadslam-report: %s\n", e.what());
    return 1;
  }
  return 0;
}
