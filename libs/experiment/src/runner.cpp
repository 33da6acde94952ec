#include "roadslam/experiment/runner.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <filesystem>
#include <map>
#include <thread>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/progress.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/experiment/run_job.h"

namespace fs = std::filesystem;

namespace roadslam::experiment {
namespace {

using Clock = std::chrono::steady_clock;

struct Running {
  const Job* job;
  Clock::time_point start;
};

pid_t spawn(const Job& job, const std::string& program) {
  const std::string log = job.dir + "/log.txt";
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("cannot start a job process: fork failed");
  if (pid == 0) {
    setpgid(0, 0);  // its own group: a timeout kills the job and anything it started
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | (program.empty() ? O_TRUNC : O_APPEND), 0644);  // run-job truncates it
    if (fd >= 0) dup2(fd, 1), dup2(fd, 2), close(fd);
    const int null = open("/dev/null", O_RDONLY);
    if (null >= 0) dup2(null, 0), close(null);
    if (program.empty()) {
      // The job in a forked copy of this process: a crash still costs this job alone, and no exec
      // pays the ~0.1 s start of a program linked to MRPT and OpenCV again (bench/experiment_overhead.sh).
      int code = 0;
      try {
        std::cout << runJob(job.dir).dump(2) << std::endl;
      } catch (const std::exception& e) {
        std::cerr << "roadslam-experiment run-job: " << e.what() << std::endl;
        code = 1;
      }
      std::fflush(nullptr);
      _exit(code);
    }
    execl(program.c_str(), program.c_str(), "run-job", job.dir.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  setpgid(pid, pid);
  return pid;
}

void recordFailure(const Job& job, const std::string& reason) {
  if (fs::exists(job.dir + "/failed.json")) return;  // the job said why itself
  const nlohmann::json f = {{"key", job.key}, {"reason", reason}};
  writeFileAtomically(job.dir + "/failed.json", f.dump(2) + "\n");
}

std::string exitReason(int status) {
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  if (WIFEXITED(status)) return "exit code " + std::to_string(WEXITSTATUS(status));
  return "ended abnormally";
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

PoolOutcome runPool(const std::vector<Job>& jobs, const PoolOptions& opt) {
  PoolOutcome out;
  const auto t0 = Clock::now();
  std::map<pid_t, Running> running;
  size_t next = 0;
  ProgressBar bar("roadslam-experiment", jobs.size());
  if (!opt.progress) bar.finish();
  while (next < jobs.size() || !running.empty()) {
    if (stopRequested()) {
      for (const auto& [pid, r] : running) kill(-pid, SIGKILL);
      out.interrupted = true;
    }
    while (!out.interrupted && next < jobs.size() && running.size() < static_cast<size_t>(std::max(1, opt.jobs))) {
      const Job& j = jobs[next++];
      running[spawn(j, opt.program)] = {&j, Clock::now()};
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0 && running.count(pid)) {
      const Running r = running[pid];
      running.erase(pid);
      ++out.ran;
      out.job_s_sum += std::chrono::duration<double>(Clock::now() - r.start).count();
      const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(r.job->dir + "/metrics.json");
      if (ok) {
        ++out.ok;
      } else {
        ++out.failed;
        recordFailure(*r.job, out.interrupted ? "interrupted" : exitReason(status));
      }
      if (opt.progress) bar.update(out.ran);
      continue;
    }
    if (pid < 0 && running.empty()) break;
    for (const auto& [p, r] : running) {
      const double age = std::chrono::duration<double>(Clock::now() - r.start).count();
      if (opt.job_timeout_s > 0 && age > opt.job_timeout_s && !fs::exists(r.job->dir + "/.timed_out")) {
        writeFileAtomically(r.job->dir + "/.timed_out", "");
        const nlohmann::json f = {{"key", r.job->key}, {"reason", "timeout: still running after " + std::to_string(static_cast<int>(opt.job_timeout_s)) + " s (--job-timeout)"}};
        writeFileAtomically(r.job->dir + "/failed.json", f.dump(2) + "\n");
        ++out.timed_out;
        kill(-p, SIGKILL);
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  bar.finish();
  for (const auto& j : jobs) fs::remove(j.dir + "/.timed_out");
  out.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
  return out;
}

std::string emitParallel(const std::vector<Job>& jobs, const std::string& program, const std::string& out_dir) {
  std::string text;
  for (const auto& j : jobs) text += quote(program) + " run-job " + quote(fs::absolute(j.dir).string()) + "\n";
  const std::string path = out_dir + "/jobs.txt";
  writeFileAtomically(path, text);
  return path;
}

std::string emitSlurm(const std::vector<Job>& jobs, const std::string& program, const std::string& out_dir,
                      const std::string& name) {
  std::string list;
  for (const auto& j : jobs) list += fs::absolute(j.dir).string() + "\n";
  const std::string abs_out = fs::absolute(out_dir).string();
  writeFileAtomically(out_dir + "/slurm_jobs.txt", list);
  const std::string script =
      "#!/bin/bash\n"
      "# roadslam experiment '" + name + "': one array task per job (" + std::to_string(jobs.size()) + " jobs).\n"
      "# Submit: sbatch " + abs_out + "/slurm.sbatch; then: roadslam-experiment collect " + abs_out + "\n"
      "#SBATCH --job-name=roadslam-" + name + "\n"
      "#SBATCH --array=0-" + std::to_string(jobs.empty() ? 0 : jobs.size() - 1) + "\n"
      "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n"
      "#SBATCH --output=" + abs_out + "/slurm-%A_%a.out\n"
      "set -euo pipefail\n"
      "JOB=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" " + quote(abs_out + "/slurm_jobs.txt") + ")\n"
      "exec " + quote(program) + " run-job \"$JOB\"\n";
  const std::string path = out_dir + "/slurm.sbatch";
  writeFileAtomically(path, script);
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
  return path;
}

}  // namespace roadslam::experiment
