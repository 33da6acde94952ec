#include "roadslam/experiment/experiment.h"

#include <filesystem>
#include <stdexcept>

#include "roadslam/experiment/jobs.h"

namespace fs = std::filesystem;

namespace roadslam::experiment {

ExperimentOutcome runExperiment(const ExperimentRequest& req) {
  if (!req.emit.empty() && req.emit != "parallel" && req.emit != "slurm") {
    throw std::runtime_error("--emit '" + req.emit + "': expected parallel or slurm");
  }
  ExperimentSpec spec = loadExperiment(req.config_path);
  std::error_code ec;
  fs::create_directories(req.out_dir, ec);
  if (!fs::is_directory(req.out_dir)) throw std::runtime_error("cannot create output folder '" + req.out_dir + "': " + ec.message());
  prepareDatasets(spec, req.out_dir);
  const auto jobs = planJobs(spec, req.out_dir);
  ExperimentOutcome out;
  out.planned = jobs.size();
  std::vector<Job> todo;
  for (const auto& j : jobs) {
    if (!req.force && finished(j)) {
      ++out.skipped;
      continue;
    }
    writeJobFolder(j, spec);
    todo.push_back(j);
  }
  writePlan(spec, jobs, req.out_dir);
  if (!req.emit.empty() && req.pool.program.empty()) throw std::runtime_error("--emit needs the program's path");
  if (req.emit == "parallel") {
    out.emitted = emitParallel(todo, req.pool.program, req.out_dir);
    return out;
  }
  if (req.emit == "slurm") {
    out.emitted = emitSlurm(todo, req.pool.program, req.out_dir, spec.name);
    return out;
  }
  PoolOptions pool = req.pool;
  if (req.fork_jobs) pool.program.clear();
  out.pool = runPool(todo, pool);
  out.collected = collect(req.out_dir);
  return out;
}

}  // namespace roadslam::experiment
