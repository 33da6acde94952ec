#pragma once
/// \file runner.h
/// Running an experiment's jobs: on this machine with a pool of child processes (each job a
/// `roadslam-experiment run-job DIR`, so a crash or a hang costs that job alone), or handed to an
/// existing engine: a GNU parallel job list (`parallel --sshloginfile HOSTS < jobs.txt`) or a Slurm
/// job-array script (`sbatch slurm.sbatch`), then `roadslam-experiment collect OUT`.

#include <string>
#include <vector>

#include "roadslam/experiment/jobs.h"

namespace roadslam::experiment {

struct PoolOptions {
  /// The roadslam-experiment binary (absolute) to exec as `PROGRAM run-job DIR` per job; empty: each
  /// job runs in a forked child of this process (no exec: a process start costs ~0.1 s here).
  std::string program;
  int jobs = 1;              ///< processes at once
  double job_timeout_s = 0;  ///< a job running longer is killed and recorded as failed (0 = none) [s]
  bool progress = true;      ///< progress bar with ETA on a terminal
};

struct PoolOutcome {
  size_t ran = 0, ok = 0, failed = 0, timed_out = 0;
  double wall_s = 0;      ///< the pool's wall time [s]
  double job_s_sum = 0;   ///< the jobs' wall times summed [s]
  bool interrupted = false;
};

/// Runs \p jobs (those not finished; the caller filters) with the pool. A job that exits non-zero,
/// dies by a signal or passes the timeout gets failed.json with the reason; its log.txt stays. The
/// others go on. SIGINT/SIGTERM stop the pool: running jobs are killed, none is started.
PoolOutcome runPool(const std::vector<Job>& jobs, const PoolOptions& opt);

/// OUT/jobs.txt: one `PROGRAM run-job DIR` line per job, for GNU parallel. Returns its path.
std::string emitParallel(const std::vector<Job>& jobs, const std::string& program, const std::string& out_dir);
/// OUT/slurm.sbatch (a job array, one task per job, task i runs line i+1 of OUT/slurm_jobs.txt).
/// Returns its path.
std::string emitSlurm(const std::vector<Job>& jobs, const std::string& program, const std::string& out_dir,
                      const std::string& name);

}  // namespace roadslam::experiment
