#include "roadslam/experiment/spec.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>
#include <stdexcept>

#include "roadslam/boundary/params.h"
#include "roadslam/common/checked_config.h"
#include "roadslam/common/config.h"
#include "roadslam/jobs/map_job.h"

namespace fs = std::filesystem;

namespace roadslam::experiment {
namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    item = trim(item);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

/// Collects "FILE:LINE: what" problems so that one run names all of them.
struct Problems {
  const CheckedConfig& cfg;
  std::vector<std::string> list;
  void add(const std::string& section, const std::string& key, const std::string& what) {
    const int line = cfg.lineOf(section, key);
    list.push_back(cfg.path() + ":" + (line > 0 ? std::to_string(line) : "?") + ": " + what);
  }
};

std::string resolve(const std::string& base_dir, const std::string& p) {
  if (p.empty()) return p;
  const fs::path path(p);
  return (path.is_absolute() ? path : fs::path(base_dir) / path).lexically_normal().string();
}

Stage stageFromString(const std::string& s) {
  for (Stage st : {Stage::Odometry, Stage::Map, Stage::Bounds, Stage::Eval}) {
    if (s == toString(st)) return st;
  }
  throw std::invalid_argument("unknown stage '" + s + "' (expected odometry, map, bounds or eval)");
}

bool isNumber(const std::string& s) {
  try {
    size_t n = 0;
    std::stod(s, &n);
    return n == s.size();
  } catch (const std::exception&) {
    return false;
  }
}

/// "uniform(0.5, 1.5)" -> ("uniform", 0.5, 1.5); false when \p v is no distribution.
bool parseDistribution(const std::string& v, SweepParam& p) {
  const auto open = v.find('(');
  if (open == std::string::npos || v.back() != ')') return false;
  const std::string name = trim(v.substr(0, open));
  if (name != "uniform" && name != "loguniform" && name != "randint") return false;
  const auto args = splitList(v.substr(open + 1, v.size() - open - 2));
  if (args.size() != 2 || !isNumber(args[0]) || !isNumber(args[1])) {
    throw std::invalid_argument("'" + v + "': expected " + name + "(low, high)");
  }
  p.distribution = name, p.lo = std::stod(args[0]), p.hi = std::stod(args[1]);
  if (!(p.hi > p.lo) || (name == "loguniform" && p.lo <= 0)) {
    throw std::invalid_argument("'" + v + "': needs low < high" + std::string(name == "loguniform" ? " and low > 0" : ""));
  }
  return true;
}

void readDatasets(const CheckedConfig& cfg, const std::string& dir, ExperimentSpec& spec, Problems& pr) {
  std::vector<std::string> sections;
  cfg.getAllSections(sections);
  for (const auto& sec : sections) {
    if (sec.rfind("dataset.", 0) != 0) continue;
    Dataset d;
    d.name = sec.substr(8);
    d.input = resolve(dir, readString(cfg, sec, "input", ""));
    d.times = resolve(dir, readString(cfg, sec, "times", ""));
    d.gt = resolve(dir, readString(cfg, sec, "gt", ""));
    d.gt_times = resolve(dir, readString(cfg, sec, "gt_times", ""));
    d.gt_calib = resolve(dir, readString(cfg, sec, "gt_calib", ""));
    d.gt_boundaries = resolve(dir, readString(cfg, sec, "gt_boundaries", ""));
    d.scenario = resolve(dir, readString(cfg, sec, "scenario", ""));
    d.duration_s = readDouble(cfg, sec, "duration_s", 0.0);
    const std::string main_key = d.scenario.empty() ? "input" : "scenario";
    d.line = cfg.lineOf(sec, main_key);
    if (d.name.empty()) pr.add(sec, main_key, "a dataset section needs a name: [dataset.NAME]");
    if (d.scenario.empty() == d.input.empty()) {
      pr.add(sec, main_key, "[" + sec + "] needs exactly one of input (a recording) or scenario (a simulated drive)");
    }
    for (const auto& [key, path] : {std::pair{"input", d.input}, {"times", d.times}, {"gt", d.gt}, {"gt_times", d.gt_times},
                                    {"gt_calib", d.gt_calib}, {"gt_boundaries", d.gt_boundaries}, {"scenario", d.scenario}}) {
      if (!path.empty() && !fs::exists(path)) pr.add(sec, key, "[" + sec + "] " + key + " '" + path + "' does not exist");
    }
    if (d.duration_s < 0) pr.add(sec, "duration_s", "[" + sec + "] duration_s must be >= 0");
    if (!d.input.empty() && cfg.keyExists(sec, "duration_s"))  // never silently ignored
      pr.add(sec, "duration_s", "[" + sec + "] duration_s cuts a simulated drive (scenario); a recording (input) is used whole");
    spec.datasets.push_back(d);
  }
  if (spec.datasets.empty()) pr.list.push_back(cfg.path() + ": no [dataset.NAME] section: an experiment needs a recording");
}

void readSweep(const CheckedConfig& cfg, const std::string& dir, ExperimentSpec& spec, Problems& pr) {
  const std::string mode = readString(cfg, "sweep", "mode", "grid");
  if (mode == "grid") spec.mode = SweepMode::Grid;
  else if (mode == "zip") spec.mode = SweepMode::Zip;
  else if (mode == "random") spec.mode = SweepMode::Random;
  else pr.add("sweep", "mode", "[sweep] mode = '" + mode + "': expected grid, zip or random");
  spec.samples = static_cast<size_t>(std::max(0, readInt(cfg, "sweep", "samples", 0)));
  spec.seed = static_cast<uint64_t>(readInt(cfg, "sweep", "seed", 1));
  if (spec.mode == SweepMode::Random && spec.samples == 0) pr.add("sweep", "mode", "[sweep] mode = random needs samples = N > 0");
  std::vector<std::string> keys;
  cfg.getAllKeys("sweep", keys);
  std::vector<std::string> known;
  try {
    known = knownConfigKeys(spec.base_config);
  } catch (const std::exception& e) {
    pr.add("experiment", "base_config", std::string("base_config: ") + e.what());
  }
  known.push_back("experiment.base_config");
  size_t zip_len = 0;
  for (const auto& k : keys) {
    if (k == "mode" || k == "samples" || k == "seed") continue;
    SweepParam p;
    const auto dot = k.find('.');
    p.section = dot == std::string::npos ? "" : k.substr(0, dot);
    p.key = dot == std::string::npos ? k : k.substr(dot + 1);
    p.line = cfg.lineOf("sweep", k);
    const std::string raw = readString(cfg, "sweep", k, "");
    if (!known.empty() && std::find(known.begin(), known.end(), k) == known.end()) {
      const std::string near = nearestName(k, known);
      pr.add("sweep", k, "unknown key '" + k + "' in [sweep]: no component of a job reads it" +
                             (near.empty() ? "" : " (nearest known: " + near + ")"));
      continue;
    }
    try {
      if (spec.mode == SweepMode::Random && parseDistribution(raw, p)) {
        spec.sweep.push_back(p);
        continue;
      }
    } catch (const std::invalid_argument& e) {
      pr.add("sweep", k, "[sweep] " + k + " = " + e.what());
      continue;
    }
    p.values = splitList(raw);
    if (p.values.empty()) pr.add("sweep", k, "[sweep] " + k + " has no value");
    if (k == "experiment.base_config") {
      for (auto& v : p.values) {
        v = resolve(dir, v);
        if (!fs::exists(v)) pr.add("sweep", k, "[sweep] " + k + ": '" + v + "' does not exist");
      }
    }
    if (spec.mode == SweepMode::Zip) {
      if (zip_len && p.values.size() != zip_len) {
        pr.add("sweep", k, "[sweep] mode = zip: " + k + " has " + std::to_string(p.values.size()) +
                               " values, the keys before it " + std::to_string(zip_len));
      }
      zip_len = std::max(zip_len, p.values.size());
    }
    spec.sweep.push_back(p);
  }
}

}  // namespace

const char* toString(Stage s) {
  switch (s) {
    case Stage::Odometry: return "odometry";
    case Stage::Map: return "map";
    case Stage::Bounds: return "bounds";
    case Stage::Eval: return "eval";
  }
  return "?";
}

bool ExperimentSpec::has(Stage s) const { return std::find(stages.begin(), stages.end(), s) != stages.end(); }

std::vector<std::string> knownConfigKeys(const std::string& config_path) {
  const auto cfg = loadIniFile(config_path);
  mrpt::config::CConfigFileMemory all(jobs::effectiveMapConfig(*cfg));
  boundary::Params bp;
  bp.loadFromConfigFile(*cfg);
  bp.saveToConfigFile(all);
  std::vector<std::string> sections, keys, out;
  all.getAllSections(sections);
  for (const auto& s : sections) {
    all.getAllKeys(s, keys);
    for (const auto& k : keys) out.push_back(s + "." + k);
  }
  return out;
}

ExperimentSpec loadExperiment(const std::string& path) {
  if (!fs::is_regular_file(path)) throw std::runtime_error("experiment '" + path + "' does not exist");
  const auto cfg = loadIniFile(path);
  const std::string dir = fs::absolute(path).parent_path().string();
  ExperimentSpec spec;
  spec.path = fs::absolute(path).lexically_normal().string();
  Problems pr{*cfg, {}};
  spec.name = readString(*cfg, "experiment", "name", fs::path(path).stem().string());
  spec.base_config = resolve(dir, readString(*cfg, "experiment", "base_config", ""));
  if (spec.base_config.empty()) pr.add("experiment", "name", "[experiment] base_config is missing");
  else if (!fs::is_regular_file(spec.base_config)) pr.add("experiment", "base_config", "base_config '" + spec.base_config + "' does not exist");
  for (const auto& s : splitList(readString(*cfg, "experiment", "stages", "odometry, eval"))) {
    try {
      spec.stages.push_back(stageFromString(s));
    } catch (const std::invalid_argument& e) {
      pr.add("experiment", "stages", std::string("[experiment] stages: ") + e.what());
    }
  }
  const int max_frames = readInt(*cfg, "experiment", "max_frames", 0);
  if (max_frames < 0) pr.add("experiment", "max_frames", "[experiment] max_frames must be >= 0");
  spec.max_frames = static_cast<size_t>(std::max(0, max_frames));
  const std::string bp = readString(*cfg, "experiment", "bounds_poses", "auto");
  if (bp == "auto") spec.bounds_poses = BoundsPoses::Auto;
  else if (bp == "gt") spec.bounds_poses = BoundsPoses::Gt;
  else if (bp == "odometry") spec.bounds_poses = BoundsPoses::Odometry;
  else pr.add("experiment", "bounds_poses", "[experiment] bounds_poses = '" + bp + "': expected auto, gt or odometry");
  readDatasets(*cfg, dir, spec, pr);
  if (pr.list.empty() || fs::is_regular_file(spec.base_config)) readSweep(*cfg, dir, spec, pr);
  for (const auto& w : cfg->unknownEntries()) pr.list.push_back(w);
  if (spec.has(Stage::Eval)) {
    for (const auto& d : spec.datasets) {
      if (d.scenario.empty() && d.gt.empty() && !(spec.has(Stage::Bounds) && !d.gt_boundaries.empty())) {
        pr.list.push_back(spec.path + ":" + std::to_string(d.line) + ": [dataset." + d.name +
                          "] has no ground truth (gt) for the eval stage");
      }
    }
  }
  if (!pr.list.empty()) {
    std::string msg;
    for (const auto& p : pr.list) msg += (msg.empty() ? "" : "\n") + p;
    throw std::runtime_error(msg);
  }
  return spec;
}

}  // namespace roadslam::experiment
