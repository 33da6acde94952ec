#pragma once
/// \file jobs.h
/// An experiment's jobs: one per (configuration of the sweep, dataset), each with its own folder
/// OUT/jobs/<dataset>-<key>/ holding job.json (what to run), config_used.ini (the effective config: the
/// base with the sweep's values), and after the run: the stages' outputs, log.txt and metrics.json
/// (or failed.json). The key is a hash of the effective config, the dataset, the stages and the
/// program version: a rerun finds a finished job by it and skips it.

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roadslam/experiment/spec.h"

namespace roadslam::experiment {

struct Job {
  size_t index = 0;        ///< order in the plan
  size_t variant = 0;      ///< which configuration of the sweep
  std::string dataset;     ///< Dataset::name
  std::map<std::string, std::string> params;  ///< swept "section.key" -> value
  std::string config_text; ///< effective config (ini text)
  std::string key;         ///< hash, see the file comment
  std::string dir;         ///< OUT/jobs/<dataset>-<key[0:10]>
};

/// The sweep's configurations: grid (every combination, the last key fastest), zip (the i-th value
/// of every key), random (samples draws from the lists/distributions with the spec's seed). An empty
/// sweep is one configuration, the base.
std::vector<std::map<std::string, std::string>> expandSweep(const ExperimentSpec& spec);

/// Simulates the spec's simulated datasets once into OUT/data/<name> (kept when already there and
/// made from the same scenario and duration) and fills their input, gt and gt_boundaries. Checks that
/// each recorded dataset's ground truth overlaps the recording in time. Throws "FILE:LINE: ..."
/// naming the dataset's section.
void prepareDatasets(ExperimentSpec& spec, const std::string& out_dir);

/// Every job of the plan with its folder's path, in order (variants outer, datasets inner).
std::vector<Job> planJobs(const ExperimentSpec& spec, const std::string& out_dir);

/// Writes the job's folder (job.json, config_used.ini); leaves its results as they are.
void writeJobFolder(const Job& job, const ExperimentSpec& spec);

/// The job is finished with this key (metrics.json present and carrying it).
bool finished(const Job& job);

/// OUT/plan.json: the experiment, its sweep and every job (index, dataset, params, dir, key):
/// what `collect` reads back.
void writePlan(const ExperimentSpec& spec, const std::vector<Job>& jobs, const std::string& out_dir);

}  // namespace roadslam::experiment
