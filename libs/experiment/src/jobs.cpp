#include "roadslam/experiment/jobs.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/md5.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/version.h"
#include "roadslam/eval/evaluate.h"
#include "roadslam/sim/outputs.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/sources/scan_source.h"

namespace fs = std::filesystem;

namespace roadslam::experiment {
namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + path + "'");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A value drawn from [0, 1) from the raw 64 bits of mt19937_64: the same on every platform (the
/// standard distributions' algorithms are left to each library).
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

std::string formatValue(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string draw(const SweepParam& p, std::mt19937_64& rng) {
  const double u = unit(rng);
  if (p.distribution == "uniform") return formatValue(p.lo + u * (p.hi - p.lo));
  if (p.distribution == "loguniform") return formatValue(std::exp(std::log(p.lo) + u * (std::log(p.hi) - std::log(p.lo))));
  if (p.distribution == "randint") return std::to_string(static_cast<long long>(std::floor(p.lo + u * (p.hi - p.lo + 1))));
  return p.values[std::min(p.values.size() - 1, static_cast<size_t>(u * static_cast<double>(p.values.size())))];
}

nlohmann::json datasetJson(const Dataset& d) {
  return {{"name", d.name}, {"input", d.input}, {"times", d.times}, {"gt", d.gt}, {"gt_times", d.gt_times},
          {"gt_calib", d.gt_calib}, {"gt_boundaries", d.gt_boundaries}, {"scenario", d.scenario},
          {"duration_s", d.duration_s}};
}

/// What identifies a dataset's data: a simulated one by its scenario's text and duration, a
/// recording by its path and size.
std::string datasetIdentity(const Dataset& d) {
  if (!d.scenario.empty()) return "sim:" + mrpt::system::md5(readText(d.scenario)) + ":" + formatValue(d.duration_s);
  std::error_code ec;
  const auto size = fs::is_regular_file(d.input) ? fs::file_size(d.input, ec) : 0;
  return "rec:" + d.input + ":" + std::to_string(size) + ":" + d.gt + ":" + d.gt_times + ":" + d.gt_calib + ":" + d.gt_boundaries;
}

void simulate(Dataset& d, const std::string& dir) {
  const nlohmann::json made = {{"scenario_md5", mrpt::system::md5(readText(d.scenario))}, {"duration_s", d.duration_s}};
  const std::string marker = dir + "/dataset.json";
  bool have = false;
  if (fs::exists(marker)) {
    try {
      have = nlohmann::json::parse(readText(marker)) == made;
    } catch (const std::exception&) {
    }
  }
  if (!have) {
    auto p = sim::ScenarioParams::fromFile(d.scenario);
    if (d.duration_s > 0) p.duration_s = d.duration_s;
    sim::Simulator s(p);
    sim::OutputOptions opt;
    opt.dir = dir;
    sim::runToDirectory(s, opt);
    writeFileAtomically(marker, made.dump() + "\n");
  }
  d.input = fs::exists(dir + "/velodyne.pcap") ? dir + "/velodyne.pcap" : dir + "/velodyne";
  if (!fs::exists(d.input)) throw std::runtime_error("simulating '" + d.scenario + "' gave no recording in " + dir);
  if (fs::exists(dir + "/gt_trajectory.tum")) d.gt = dir + "/gt_trajectory.tum";
  if (fs::exists(dir + "/gt_boundaries.json")) d.gt_boundaries = dir + "/gt_boundaries.json";
}

/// The recording and its GT must share a clock: a GT of another drive (or on another clock) would
/// pair no pose and score nothing.
void checkGtOverlap(const ExperimentSpec& spec, const Dataset& d) {
  if (d.gt.empty()) return;
  const auto gt = eval::readTrajectoryAnyFormat(d.gt, d.gt_times);
  if (gt.stamps_s.empty()) return;  // KITTI poses without times: paired by index
  const auto cfg = loadIniFile(spec.base_config);
  auto src = sources::openScanSource(d.input, *cfg, d.times);
  const auto first = src->next();
  if (!first) throw std::runtime_error(spec.path + ":" + std::to_string(d.line) + ": [dataset." + d.name + "] input '" + d.input + "' gives no sweep");
  const double t0 = gt.stamps_s.front(), t1 = gt.stamps_s.back();
  // The recording starts inside the GT, or at most an hour before it (a GT that starts late).
  if (first->stamp_s > t1 + 1.0 || first->stamp_s < t0 - 3600.0) {
    char b[256];
    std::snprintf(b, sizeof b, "the GT covers %.3f-%.3f s, the recording starts at %.3f s: they do not overlap", t0, t1,
                  first->stamp_s);
    throw std::runtime_error(spec.path + ":" + std::to_string(d.line) + ": [dataset." + d.name + "] gt '" + d.gt + "': " + b);
  }
}

}  // namespace

std::vector<std::map<std::string, std::string>> expandSweep(const ExperimentSpec& spec) {
  std::vector<std::map<std::string, std::string>> out;
  if (spec.sweep.empty()) return {{}};
  if (spec.mode == SweepMode::Zip) {
    for (size_t i = 0; i < spec.sweep.front().values.size(); ++i) {
      std::map<std::string, std::string> c;
      for (const auto& p : spec.sweep) c[p.name()] = p.values[i];
      out.push_back(c);
    }
  } else if (spec.mode == SweepMode::Random) {
    std::mt19937_64 rng(spec.seed);
    for (size_t i = 0; i < spec.samples; ++i) {
      std::map<std::string, std::string> c;
      for (const auto& p : spec.sweep) c[p.name()] = draw(p, rng);
      out.push_back(c);
    }
  } else {
    out.push_back({});
    for (const auto& p : spec.sweep) {
      std::vector<std::map<std::string, std::string>> next;
      for (const auto& c : out) {
        for (const auto& v : p.values) {
          auto d = c;
          d[p.name()] = v;
          next.push_back(d);
        }
      }
      out = std::move(next);
    }
  }
  return out;
}

void prepareDatasets(ExperimentSpec& spec, const std::string& out_dir) {
  for (auto& d : spec.datasets) {
    if (!d.scenario.empty()) {
      simulate(d, out_dir + "/data/" + d.name);
    } else {
      checkGtOverlap(spec, d);
    }
  }
}

std::vector<Job> planJobs(const ExperimentSpec& spec, const std::string& out_dir) {
  std::vector<Job> jobs;
  const auto variants = expandSweep(spec);
  std::string stages;
  for (Stage s : spec.stages) stages += std::string(toString(s)) + ",";
  const std::string program = std::string(projectVersion()) + ":" + gitCommit();
  for (size_t v = 0; v < variants.size(); ++v) {
    std::string base = spec.base_config;
    if (auto it = variants[v].find("experiment.base_config"); it != variants[v].end()) base = it->second;
    for (const auto& d : spec.datasets) {
      mrpt::config::CConfigFileMemory cfg(readText(base));
      for (const auto& [name, value] : variants[v]) {
        if (name == "experiment.base_config") continue;
        const auto dot = name.find('.');
        cfg.write(name.substr(0, dot), name.substr(dot + 1), value);
      }
      Job j;
      j.index = jobs.size(), j.variant = v, j.dataset = d.name, j.params = variants[v];
      j.config_text = cfg.getContent();
      j.key = mrpt::system::md5(j.config_text + "\n" + datasetIdentity(d) + "\n" + stages + "\n" +
                                std::to_string(spec.max_frames) + ":" + std::to_string(static_cast<int>(spec.bounds_poses)) +
                                "\n" + program);
      j.dir = out_dir + "/jobs/" + d.name + "-" + j.key.substr(0, 10);
      jobs.push_back(j);
    }
  }
  return jobs;
}

void writeJobFolder(const Job& job, const ExperimentSpec& spec) {
  std::error_code ec;
  fs::create_directories(job.dir, ec);
  if (!fs::is_directory(job.dir)) throw std::runtime_error("cannot create job folder '" + job.dir + "': " + ec.message());
  writeFileAtomically(job.dir + "/config_used.ini", job.config_text);
  const Dataset* d = nullptr;
  for (const auto& x : spec.datasets) d = x.name == job.dataset ? &x : d;
  nlohmann::json stages = nlohmann::json::array();
  for (Stage s : spec.stages) stages.push_back(toString(s));
  const char* bp = spec.bounds_poses == BoundsPoses::Gt ? "gt" : spec.bounds_poses == BoundsPoses::Odometry ? "odometry" : "auto";
  const nlohmann::json j = {{"experiment", spec.name}, {"index", job.index}, {"variant", job.variant},
                            {"key", job.key}, {"params", job.params}, {"dataset", datasetJson(*d)},
                            {"stages", stages}, {"max_frames", spec.max_frames}, {"bounds_poses", bp}};
  writeFileAtomically(job.dir + "/job.json", j.dump(2) + "\n");
}

bool finished(const Job& job) {
  try {
    return nlohmann::json::parse(readText(job.dir + "/metrics.json")).value("key", "") == job.key;
  } catch (const std::exception&) {
    return false;
  }
}

void writePlan(const ExperimentSpec& spec, const std::vector<Job>& jobs, const std::string& out_dir) {
  nlohmann::json js = nlohmann::json::array();
  for (const auto& j : jobs) {
    js.push_back({{"index", j.index}, {"variant", j.variant}, {"dataset", j.dataset}, {"params", j.params},
                  {"key", j.key}, {"dir", fs::relative(j.dir, out_dir).string()}});
  }
  nlohmann::json swept = nlohmann::json::array();
  for (const auto& p : spec.sweep) swept.push_back(p.name());
  const nlohmann::json plan = {{"experiment", spec.name}, {"spec", spec.path}, {"base_config", spec.base_config},
                               {"swept", swept}, {"jobs", js}};
  writeFileAtomically(out_dir + "/plan.json", plan.dump(2) + "\n");
}

}  // namespace roadslam::experiment
