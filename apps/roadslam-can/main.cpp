// roadslam-can: CAN logs and DBC files - decode, summarize, dead-reckon, export to rawlog.
#include <roadslam/can/decode_report.h>
#include <roadslam/can/log_info.h>
#include <roadslam/vehicle/jobs.h>

#include <CLI/CLI.hpp>
#include <roadslam/common/cli.h>

#include <iostream>
#include <memory>
#include <sstream>

using namespace roadslam;

int main(int argc, char** argv) {
  CLI::App app{"CAN bus tools: decode candump logs with a DBC, summarize them, dead-reckon and export to MRPT rawlogs"};
  roadslam::addVersionFlag(app, "roadslam-can");
  app.require_subcommand(1);
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return "roadslam-can: " + std::string(e.what()) + "\n"; });
  std::string dbc, log, vehicle, out, data_root, gnss, signals;
  bool csv = false, json = false, no_scale = false;

  auto* dec = app.add_subcommand("decode", "decode every frame of LOG with a DBC");
  dec->add_option("--dbc", dbc, "DBC file")->required()->check(CLI::ExistingFile);
  dec->add_option("LOG,--input", log, "candump log")->required()->check(CLI::ExistingFile);
  dec->add_option("--signals", signals, "comma-separated SIGNAL or MESSAGE.SIGNAL names (default: all)");
  dec->add_flag("--csv", csv, "CSV, one row per signal");
  dec->add_flag("--json", json, "JSON lines, one object per frame");

  auto* info = app.add_subcommand("info", "ids, rates, unknown ids, DLC mismatches and gaps of LOG");
  info->add_option("LOG,--input", log, "candump log")->required()->check(CLI::ExistingFile);
  info->add_option("--dbc", dbc, "DBC file (unknown ids, DLC mismatches)")->check(CLI::ExistingFile);
  info->add_flag("--json", json, "JSON output");

  auto* odo = app.add_subcommand("odometry", "dead reckoning from wheel speeds and yaw rate (or steering)");
  odo->add_option("--vehicle", vehicle, "ini/vehicles/<car>.ini")->required()->check(CLI::ExistingFile);
  odo->add_option("LOG,--input", log, "candump log")->required()->check(CLI::ExistingFile);
  odo->add_option("--out", out, "trajectory, TUM format (config used goes to OUT.ini)")->required();
  odo->add_option("--gnss", gnss, "u-blox fix CSV: estimate yaw-rate bias and wheel-speed scale")->check(CLI::ExistingFile);
  odo->add_flag("--no-scale", no_scale, "with --gnss: estimate but do not apply the wheel-speed scale");

  auto* raw = app.add_subcommand("to-rawlog", "MRPT rawlog (odometry, IMU, GPS) + lossless candump sidecar");
  raw->add_option("--vehicle", vehicle, "ini/vehicles/<car>.ini")->required()->check(CLI::ExistingFile);
  raw->add_option("LOG,--input", log, "candump log")->required()->check(CLI::ExistingFile);
  raw->add_option("OUT", out, "output .rawlog")->required();
  for (auto* c : {odo, raw}) c->add_option("--data-root", data_root, "folder the ini's DBC path is relative to");

  size_t max_bad = 0;
  for (auto* c : {dec, info})
    c->add_option("--max-bad-lines", max_bad, "exit 2 when the log has more lines the parser cannot read (default 0)");
  CLI11_PARSE(app, argc, argv);
  // A log the user named is read whole or the run says so: bad lines above the limit fail it.
  const auto checkBad = [&](const can::CandumpStats& st) {
    if (st.bad <= max_bad) return 0;
    const auto& first = st.issues.front();
    std::cerr << "roadslam-can: " << log << ": " << st.bad << " of " << st.lines << " lines unreadable (first at line "
              << first.line << ": " << first.reason << "); --max-bad-lines " << st.bad << " accepts them\n";
    return 2;
  };
  try {
    if (*dec) {
      std::vector<std::string> sel;
      std::stringstream ss(signals);
      for (std::string s; std::getline(ss, s, ',');) sel.push_back(s);
      can::CandumpReader reader(log);
      const can::Decoder decoder(can::loadDbcFile(dbc), sel);
      const auto fmt = csv ? can::DecodeFormat::kCsv : json ? can::DecodeFormat::kJsonLines : can::DecodeFormat::kText;
      const auto counts = can::decodeLog(reader, decoder, fmt, std::cout);
      std::cerr << counts.summary() << "; " << reader.stats().bad << " bad log lines\n";
      if (const int rc = checkBad(reader.stats())) return rc;
    } else if (*info) {
      can::CandumpStats st;
      const auto frames = can::readCandumpFile(log, &st);
      std::unique_ptr<can::Database> db;
      if (!dbc.empty()) db = std::make_unique<can::Database>(can::loadDbcFile(dbc));
      const auto li = can::analyzeLog(frames, db.get());
      std::cout << (json ? can::formatLogInfoJson(li) + "\n" : can::formatLogInfoText(li));
      if (st.bad) std::cerr << st.bad << " bad log lines (first at line " << st.issues.front().line << ")\n";
      if (const int rc = checkBad(st)) return rc;
    } else if (*odo) {
      vehicle::OdometryJob job{vehicle, data_root, log, out, gnss, !no_scale, {}};
      std::cout << vehicle::runOdometryJob(job).text();
    } else {
      vehicle::RawlogJob job{vehicle, data_root, log, out, {}, {}};
      std::cout << vehicle::runRawlogJob(job).text();
    }
  } catch (const std::exception& e) {
    std::cerr << "roadslam-can: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
