#include "roadslam/jobs/sim_job.h"

#include <cstdio>
#include <stdexcept>

#include "roadslam/runfolder/manifest.h"
#include "roadslam/runfolder/output_folder.h"
#include "roadslam/sim/simulator.h"

namespace roadslam::jobs {
namespace {

constexpr const char* kSimProgram = "roadslam-sim";

/// "HOST:PORT" into the output options; throws naming the flag.
void parseUdp(const std::string& udp, double speed, sim::OutputOptions& opt) {
  if (udp.empty()) return;
  const auto colon = udp.rfind(':');
  const int port = colon == std::string::npos ? 0 : std::atoi(udp.c_str() + colon + 1);
  if (port <= 0 || port > 65535) throw std::runtime_error("--udp must be HOST:PORT, got '" + udp + "'");
  opt.udp_host = udp.substr(0, colon);
  opt.udp_port = static_cast<uint16_t>(port);
  opt.udp_speed = speed;
}

}  // namespace

SimOutcome runSimJob(const SimRequest& req) {
  SimOutcome out;
  std::vector<std::string> unknown;
  out.params = sim::ScenarioParams::fromFile(req.scenario_path, req.allow_unknown_keys ? &unknown : nullptr);
  if (req.seed) out.params.seed = *req.seed;
  if (req.duration_s) out.params.duration_s = *req.duration_s;
  sim::OutputOptions opt;
  opt.dir = req.out_dir;
  opt.top_view_png = req.top_view_png;
  opt.progress = req.progress;
  parseUdp(req.udp, req.udp_speed, opt);
  runfolder::OutputClaim claim{kSimProgram, req.scenario_path, "", "", {}, req.force};
  char id[96];
  std::snprintf(id, sizeof id, "?seed=%llu&duration_s=%g", static_cast<unsigned long long>(out.params.seed), out.params.duration_s);
  claim.input_suffix = id;
  sim::Simulator sim(out.params);  // checks the scenario before the folder is claimed
  out.warnings = runfolder::claimOutputFolder(req.out_dir, claim);
  out.warnings.insert(out.warnings.begin(), unknown.begin(), unknown.end());
  out.report = sim::runToDirectory(sim, opt);
  runfolder::Manifest m;
  m.program = kSimProgram;
  m.input = out.params.name + " seed " + std::to_string(out.params.seed);
  m.input_id = runfolder::inputId(claim);
  runfolder::writeManifest(req.out_dir, m);  // last: the folder is complete (docs/run-folder.md)
  return out;
}

std::string simSummaryText(const SimOutcome& o, const SimRequest& req) {
  const auto& s = o.report.stats;
  const auto& p = o.params;
  char line[512];
  std::string text;
  if (p.lidar.hdl64()) {
    std::snprintf(line, sizeof line, "%s seed %llu: %.1f s, hdl64, %llu sweeps in %s/velodyne, %llu points, %.1f m, %.1fx real time\n",
                  p.name.c_str(), static_cast<unsigned long long>(p.seed), s.duration_s, static_cast<unsigned long long>(s.sweeps),
                  req.out_dir.c_str(), static_cast<unsigned long long>(s.lidar.returns), s.distance_m, o.report.real_time_factor);
  } else {
    const std::string sent = req.udp.empty() ? "" : ", " + std::to_string(o.report.packets_sent) + " packets sent";
    std::snprintf(line, sizeof line, "%s seed %llu: %.1f s, %llu packets, %llu sweeps, %llu points, %.1f m, %.1fx real time%s\n",
                  p.name.c_str(), static_cast<unsigned long long>(p.seed), s.duration_s,
                  static_cast<unsigned long long>(s.data_packets), static_cast<unsigned long long>(s.sweeps),
                  static_cast<unsigned long long>(s.lidar.returns), s.distance_m, o.report.real_time_factor, sent.c_str());
  }
  text += line;
  if (o.report.can_frames > 0) {
    std::snprintf(line, sizeof line, "can.log: %zu CAN frames, DBC %s\n", o.report.can_frames, o.report.can_dbc.c_str());
    text += line;
  }
  return text;
}

}  // namespace roadslam::jobs
