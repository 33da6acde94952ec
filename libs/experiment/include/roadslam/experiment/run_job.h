#pragma once
/// \file run_job.h
/// One job of an experiment, run from its folder alone (job.json, config_used.ini), so that a local pool,
/// GNU parallel on other hosts or a Slurm array task run it the same way:
/// `roadslam-experiment run-job DIR`. Stages, in order: odometry (the pipeline's odometry only) or
/// map (odometry, pose graph, maps), bounds (poses: see BoundsPoses), eval (trajectory metrics
/// against the GT; boundary metrics against the simulator's curbs). Writes metrics.json, or
/// failed.json with the reason; the stages' outputs stay in DIR/map and DIR/bounds.

#include <nlohmann/json.hpp>
#include <string>

namespace roadslam::experiment {

/// The metrics' names, in the order of results.csv, and whether smaller is better.
struct MetricInfo {
  const char* name;
  bool lower_is_better;
  const char* unit;
};
const std::vector<MetricInfo>& metricInfos();

/// Runs the job in \p job_dir; returns its metrics (also written to metrics.json with the job's key
/// and wall time). Throws std::runtime_error on a failure of the job (after writing failed.json).
nlohmann::json runJob(const std::string& job_dir);

}  // namespace roadslam::experiment
