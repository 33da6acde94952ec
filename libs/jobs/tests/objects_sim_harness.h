#pragma once
// Harness of the objects stage end to end: roadslam-map's job with [objects] enabled on simulated drives, its
// tracks.csv scored with CLEAR MOT against the simulator's moving cars (eval::evaluateMotFiles).
// The tests' bounds are the figures measured when they were written minus a margin (docs/benchmarks.md,
// "Objects and tracking"); the targets MOTA >= 0.90 and MOTP <= 0.20 m are reached on the three drives,
// the id-switch target (<= 1 per 100 tracked s) on all three counting the cars that stayed in view (on the
// physical traffic), under CLEAR MOT on the 30 s loop and the parallel streets, not on the 90 s loop
// (3 cars back after 44-51 s around the block in 31 tracked s).
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <fstream>
#include <iostream>
#include <sstream>
#include <utility>
#include <vector>

#include "roadslam/common/atomic_file.h"
#include "roadslam/eval/mot_metrics.h"
#include "roadslam/jobs/map_job.h"
#include "sim_cache.h"

namespace roadslam::jobs::objects_test {

/// One value of the ini: [section] key = value.
struct IniEdit {
  std::string section, key, value;
};
/// Values set in ini/default.ini ({"objects", "method", "dbscan"}); each key must be in its section.
using IniEdits = std::vector<IniEdit>;

/// ini/default.ini with [objects] enabled = true (and remove_moving_from_maps as \p remove, and
/// \p edits), written into the test cache under \p tag. The values are set by section and key
/// (CConfigFileMemory, which keeps the comments), so a comment naming a key or a section is never edited.
inline std::string objectsIni(bool remove = true, const IniEdits& edits = {}, const std::string& tag = "") {
  const std::string source = std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini";
  std::ifstream in(source);
  std::stringstream ss;
  ss << in.rdbuf();
  mrpt::config::CConfigFileMemory cfg(ss.str());
  const auto set = [&](const IniEdit& e) {
    std::vector<std::string> keys;
    cfg.getAllKeys(e.section, keys);
    if (std::find(keys.begin(), keys.end(), e.key) == keys.end())
      throw std::runtime_error(source + " has no [" + e.section + "] " + e.key);
    cfg.write(e.section, e.key, e.value);
  };
  set({"objects", "enabled", "true"});
  if (!remove) set({"objects", "remove_moving_from_maps", "false"});
  for (const IniEdit& e : edits) set(e);
  const std::string path =
      std::string(ROADSLAM_BINARY_DIR) + "/test-cache/objects-on" + (remove ? "" : "-keep") + tag + ".ini";
  std::filesystem::create_directories(std::string(ROADSLAM_BINARY_DIR) + "/test-cache");
  writeFileAtomically(path, cfg.getContent());
  return path;
}

struct ObjectsRun {
  eval::MotMetrics m;
  nlohmann::json summary;
  std::string drive;  ///< the simulated drive's folder (gt_trajectory.tum, gt_objects.json)
  std::string out_dir;
};

inline ObjectsRun runObjects(const std::string& scenario, double duration_s, const std::string& name, bool maps = false,
                             bool remove = true, const IniEdits& edits = {}, const std::string& tag = "") {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/" + scenario + ".ini");
  p.duration_s = duration_s;
  const std::string drive = jobs::test::simulateOnce(p);
  jobs::MapRequest req;
  req.config_path = objectsIni(remove, edits, tag);
  req.input_path = drive + "/velodyne.pcap";
  req.out_dir = std::string(ROADSLAM_BINARY_DIR) + "/test-out/objects-" + name + (maps ? (remove ? "-maps" : "-maps-keep") : "") + tag;
  req.maps = maps;  // the objects stage needs only the odometry's poses; the removal needs the maps
  req.progress = false;
  ObjectsRun r;
  r.summary = jobs::runMapJob(req).summary;
  r.drive = drive;
  r.out_dir = req.out_dir;
  r.m = eval::evaluateMotFiles(drive + "/gt_objects.json", drive + "/gt_trajectory.tum", req.out_dir);
  std::cout << name << ": " << eval::toJson(r.m).dump() << "\nobjects stage: " << r.summary["objects"].dump() << "\n";
  return r;
}

inline bool hasNaN(const std::string& path) {
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    if (line.find("nan") != std::string::npos || line.find("inf") != std::string::npos) return true;
  }
  return false;
}

}  // namespace roadslam::jobs::objects_test
