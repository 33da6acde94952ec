#pragma once
/// \file sim_job.h
/// The job behind `roadslam-sim`: a scenario simulated into an output folder (sim/outputs.h lists
/// its files) that it claims first (runfolder/output_folder.h: a new or empty folder, or its own
/// earlier run of the same scenario, seed and duration) and marks complete last (run.json). A stop
/// signal ends the drive early: the files then cover the part simulated, summary.json says
/// "interrupted".

#include <cstdint>
#include <optional>
#include <string>

#include "roadslam/sim/outputs.h"

namespace roadslam::jobs {

struct SimRequest {
  std::string scenario_path;            ///< scenario ini (ini/sim/*.ini)
  std::string out_dir;
  std::optional<uint64_t> seed;         ///< overrides [scenario] seed
  std::optional<double> duration_s;     ///< overrides [scenario] duration_s (0 = the whole route)
  std::string udp;                      ///< HOST:PORT to stream the data packets to; empty = none
  double udp_speed = 1.0;               ///< pace as a multiple of real time
  std::string top_view_png;
  bool force = false;                   ///< write into a folder another run wrote (output_folder.h)
  bool progress = true;                 ///< progress bar on stderr when it is a terminal
  bool allow_unknown_keys = false;      ///< unknown scenario keys are warnings, not errors
};

struct SimOutcome {
  sim::ScenarioParams params;  ///< as run (overrides applied)
  sim::RunReport report;
  std::vector<std::string> warnings;
};

/// Runs \p req; throws std::runtime_error naming the file, key or folder on bad input.
SimOutcome runSimJob(const SimRequest& req);

/// The one-paragraph summary roadslam-sim prints.
std::string simSummaryText(const SimOutcome& o, const SimRequest& req);

}  // namespace roadslam::jobs
