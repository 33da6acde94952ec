// roadslam-experiment: parameter sweeps over recordings, scored, on this machine or a cluster.
#include <fcntl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>

#include "roadslam/common/cli.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/experiment/experiment.h"
#include "roadslam/experiment/run_job.h"

namespace ex = roadslam::experiment;

namespace {

int runJobCommand(const std::string& dir) {
  // The job's own log, whoever started it (the pool, GNU parallel, a Slurm task).
  const int fd = open((dir + "/log.txt").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) dup2(fd, 1), dup2(fd, 2), close(fd);
  try {
    const auto m = ex::runJob(dir);
    std::cout << m.dump(2) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "roadslam-experiment run-job: " << e.what() << "\n";
    return 1;
  }
}

void printCollected(const ex::Collected& c, const std::string& out) {
  std::cout << "jobs " << c.jobs << ": ok " << c.ok << ", failed " << c.failed << ", not run " << c.missing << "\n"
            << "results: " << out << "/results.csv, " << out << "/results.json, " << out << "/report.html\n";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ini-configured experiments: sweeps over recordings, scored, run here or on a cluster"};
  roadslam::addVersionFlag(app, "roadslam-experiment");
  ex::ExperimentRequest req;
  bool quiet = false;
  app.add_option("--config", req.config_path, "experiment ini (e.g. ini/experiments/voxel-size.ini)")->check(CLI::ExistingFile);
  app.add_option("--out", req.out_dir, "output folder (created when missing; reruns skip finished jobs)");
  app.add_option("--jobs", req.pool.jobs, "jobs at once on this machine")->check(CLI::PositiveNumber);
  app.add_option("--job-timeout", req.pool.job_timeout_s, "kill a job after this many seconds and record it failed (0 = none)");
  app.add_flag("--force", req.force, "rerun finished jobs too");
  app.add_option("--emit", req.emit, "write the jobs for another engine instead of running them: parallel | slurm")
      ->check(CLI::IsMember({"parallel", "slurm"}));
  app.add_flag("--quiet", quiet, "no progress bar and no summary on stdout");
  std::string job_dir, collect_dir;
  auto* run_job = app.add_subcommand("run-job", "run one job folder (what the pool, GNU parallel and Slurm call)");
  run_job->add_option("DIR", job_dir, "job folder (OUT/jobs/...)")->required()->check(CLI::ExistingDirectory);
  auto* collect = app.add_subcommand("collect", "gather job folders into results.csv/json and report.html");
  collect->add_option("DIR", collect_dir, "experiment output folder")->required()->check(CLI::ExistingDirectory);
  CLI11_PARSE(app, argc, argv);
  roadslam::installStopSignalHandlers();
  if (*run_job) return runJobCommand(job_dir);
  try {
    if (*collect) {
      printCollected(ex::collect(collect_dir), collect_dir);
      return 0;
    }
    if (req.config_path.empty() || req.out_dir.empty()) {
      std::cerr << "roadslam-experiment: --config and --out are required (or: run-job DIR, collect DIR)\n";
      return 2;
    }
    req.pool.program = std::filesystem::read_symlink("/proc/self/exe").string();
    req.pool.progress = !quiet;
    const auto out = ex::runExperiment(req);
    if (!out.emitted.empty()) {
      std::cout << out.planned << " jobs planned, " << out.skipped << " already finished; wrote " << out.emitted << "\n"
                << (req.emit == "slurm" ? "submit: sbatch " + out.emitted : "run: parallel < " + out.emitted +
                                                                                 " (or parallel --sshloginfile HOSTS < ...)")
                << "\nthen: roadslam-experiment collect " << req.out_dir << "\n";
      return 0;
    }
    if (!quiet) {
      std::cout << out.planned << " jobs planned, " << out.skipped << " already finished, " << out.pool.ran << " run in "
                << out.pool.wall_s << " s (" << out.pool.timed_out << " timed out)\n";
      printCollected(out.collected, req.out_dir);
    }
    if (out.pool.interrupted) return 130;
    return out.collected.failed ? 3 : 0;
  } catch (const std::exception& e) {
    std::cerr << "roadslam-experiment: " << e.what() << "\n";
    return 1;
  }
}
