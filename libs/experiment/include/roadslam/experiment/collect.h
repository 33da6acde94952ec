#pragma once
/// \file collect.h
/// Gathers an experiment's job folders (OUT/plan.json, each job's metrics.json or failed.json)
/// into OUT/results.csv, OUT/results.json (parameters, metrics and status per job; the best
/// configuration per metric) and OUT/report.html (one self-contained page: the best
/// configurations, each metric against the first swept parameter per dataset, every job, the
/// failed jobs with the end of their logs). The same whether the jobs ran here, under GNU parallel
/// or as a Slurm array.

#include <nlohmann/json.hpp>
#include <string>

namespace roadslam::experiment {

struct Collected {
  size_t jobs = 0, ok = 0, failed = 0, missing = 0;  ///< missing: never ran (no metrics, no failure)
  nlohmann::json results;                            ///< results.json's content
};

/// Throws std::runtime_error naming OUT/plan.json when it is missing or unreadable.
Collected collect(const std::string& out_dir);

}  // namespace roadslam::experiment
