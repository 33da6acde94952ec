#include "roadslam/experiment/run_job.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/eval/boundary_metrics.h"
#include "roadslam/eval/evaluate.h"
#include "roadslam/jobs/bounds_job.h"
#include "roadslam/jobs/map_job.h"
#include "roadslam/runfolder/run_folder.h"

namespace fs = std::filesystem;

namespace roadslam::experiment {
namespace {

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read '" + path + "'");
  return nlohmann::json::parse(in);
}

bool hasStage(const nlohmann::json& job, const std::string& s) {
  for (const auto& x : job["stages"]) {
    if (x == s) return true;
  }
  return false;
}

/// The fields every job request shares: the job's config, its dataset, a sub-folder for the outputs.
template <class Request>
Request jobRequest(const std::string& dir, const nlohmann::json& job, const std::string& sub) {
  const auto& d = job["dataset"];
  Request req;
  req.config_path = dir + "/config_used.ini";
  req.input_path = d["input"];
  req.times_path = d["times"];
  req.out_dir = dir + "/" + sub;
  req.max_frames = job["max_frames"];
  req.progress = false;
  return req;
}

void runTrajectoryStage(const std::string& dir, const nlohmann::json& job, bool maps, nlohmann::json& m) {
  auto req = jobRequest<jobs::MapRequest>(dir, job, "map");
  req.maps = maps;
  jobs::runMapJob(req);
  const runfolder::MapSummary s = runfolder::openMapRun(req.out_dir).mapSummary();  // the folder as it was written
  m["frames"] = s.frames;
  m["failed_frames"] = s.byStatus("not_converged") + s.byStatus("empty");
  m["degenerate_frames"] = s.byStatus("degenerate");
  m["ms_per_frame_p50"] = s.ms_per_frame_p50;
  m["ms_per_frame_p95"] = s.ms_per_frame_p95;
  if (maps) m["loop_closures"] = s.loop_closures.value_or(0);
}

void runBoundsStage(const std::string& dir, const nlohmann::json& job, nlohmann::json& m) {
  const auto& d = job["dataset"];
  auto req = jobRequest<jobs::BoundsRequest>(dir, job, "bounds");
  req.png_every = 0;
  const std::string poses = job["bounds_poses"];
  const std::string own_tum = dir + "/map/" + runfolder::kTrajectoryTum;
  const bool own = fs::exists(own_tum);
  if (poses == "gt" || (poses == "auto" && !own)) req.trajectory_path = d["gt"];
  if (poses == "auto" && own) req.trajectory_path = own_tum;
  if (poses == "gt" && req.trajectory_path.empty()) throw std::runtime_error("bounds_poses = gt, but the dataset has no gt");
  const runfolder::BoundsSummary s = runfolder::boundsSummaryFromJson(jobs::runBoundsJob(req), req.out_dir + "/summary.json");
  m["both_found_rate"] = s.both_found_rate;
  m["bounds_ms_per_frame"] = s.ms_per_frame_mean;
}

void runEvalStage(const std::string& dir, const nlohmann::json& job, nlohmann::json& m) {
  const auto& d = job["dataset"];
  const std::string est = dir + "/map/" + runfolder::kTrajectoryTum;
  if (!d["gt"].get<std::string>().empty() && fs::exists(est)) {
    eval::EvalRequest req;
    req.gt_path = d["gt"], req.gt_times_path = d["gt_times"], req.gt_calib_path = d["gt_calib"];
    req.est_path = est;
    const auto o = eval::evaluate(req);
    m["rte_percent"] = o.metrics.rte_percent;
    m["rre_deg_per_100m"] = o.metrics.rre_deg_per_100m;
    m["ate_m"] = o.metrics.ate_rmse_m;
    m["path_length_m"] = o.metrics.path_length_m;
    for (const auto& w : o.warnings) m["warnings"].push_back("eval: " + w);
  }
  const std::string jsonl = dir + "/bounds/" + runfolder::kBoundariesJsonl;
  if (!d["gt_boundaries"].get<std::string>().empty() && !d["gt"].get<std::string>().empty() && fs::exists(jsonl)) {
    const auto b = eval::evaluateBoundaryFiles(d["gt_boundaries"], d["gt"], jsonl);
    m["boundary_detection_rate"] = b.detection_rate;
    m["lateral_error_mean_m"] = b.lateral_error_mean_m;
    m["lateral_error_p95_m"] = b.lateral_error_p95_m;
  }
}

}  // namespace

const std::vector<MetricInfo>& metricInfos() {
  static const std::vector<MetricInfo> k = {
      {"rte_percent", true, "%"},          {"ate_m", true, "m"},
      {"rre_deg_per_100m", true, "deg/100m"}, {"ms_per_frame_p50", true, "ms"},
      {"ms_per_frame_p95", true, "ms"},    {"failed_frames", true, ""},
      {"degenerate_frames", true, ""},     {"loop_closures", false, ""},
      {"both_found_rate", false, ""},      {"boundary_detection_rate", false, ""},
      {"lateral_error_mean_m", true, "m"}, {"lateral_error_p95_m", true, "m"},
      {"bounds_ms_per_frame", true, "ms"}, {"frames", false, ""},
      {"wall_s", true, "s"}};
  return k;
}

nlohmann::json runJob(const std::string& dir) {
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json job = readJson(dir + "/job.json");
  fs::remove(dir + "/metrics.json");
  fs::remove(dir + "/failed.json");
  nlohmann::json m = {{"key", job["key"]}, {"warnings", nlohmann::json::array()}};
  try {
    if (hasStage(job, "map")) runTrajectoryStage(dir, job, true, m);
    else if (hasStage(job, "odometry")) runTrajectoryStage(dir, job, false, m);
    if (hasStage(job, "bounds")) runBoundsStage(dir, job, m);
    if (hasStage(job, "eval")) runEvalStage(dir, job, m);
  } catch (const std::exception& e) {
    const nlohmann::json f = {{"key", job["key"]}, {"reason", e.what()}};
    writeFileAtomically(dir + "/failed.json", f.dump(2) + "\n");
    throw;
  }
  m["wall_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  writeFileAtomically(dir + "/metrics.json", m.dump(2) + "\n");
  return m;
}

}  // namespace roadslam::experiment
