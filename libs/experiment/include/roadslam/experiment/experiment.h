#pragma once
/// \file experiment.h
/// `roadslam-experiment --config EXP.ini --out DIR`: check the experiment (spec.h), simulate its
/// simulated datasets once, plan its jobs (jobs.h), run those not finished (runner.h) or emit them
/// for GNU parallel / Slurm, and collect the results (collect.h).

#include <string>

#include "roadslam/experiment/collect.h"
#include "roadslam/experiment/runner.h"

namespace roadslam::experiment {

struct ExperimentRequest {
  std::string config_path;   ///< EXP.ini
  std::string out_dir;
  PoolOptions pool;          ///< program (required with emit), jobs, job timeout, progress
  bool fork_jobs = true;     ///< local pool: jobs in forked children (no exec) rather than `program run-job`
  bool force = false;        ///< rerun finished jobs too
  std::string emit;          ///< "" = run here; "parallel" or "slurm": write the job list / script only
};

struct ExperimentOutcome {
  size_t planned = 0, skipped = 0;  ///< jobs in the plan, jobs already finished (not rerun)
  PoolOutcome pool;
  std::string emitted;              ///< the job list / script written with --emit
  Collected collected;              ///< empty with --emit
};

/// Throws std::runtime_error before any job starts on a bad experiment (file:line), a missing
/// dataset, a GT that does not overlap its recording; jobs' failures are counted, never thrown.
ExperimentOutcome runExperiment(const ExperimentRequest& req);

}  // namespace roadslam::experiment
