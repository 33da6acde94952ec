// Every shipped ini under ini/ (vehicles and simulator scenarios included) is loaded by the
// component that reads it, saved, the saved text loaded again and saved again: the two texts are
// identical (load and save are each other's inverse on what we ship), and the shipped file holds no
// key that its components do not read. A new ini under ini/ must be given its reader here.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "roadslam/boundary/params.h"
#include "roadslam/common/checked_config.h"
#include "roadslam/common/config.h"
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/experiment/jobs.h"
#include "roadslam/grabber/params.h"
#include "roadslam/jobs/map_job.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/preprocess/chain.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/vehicle/params.h"
#include "roadslam/velodyne/decoder_params.h"

namespace fs = std::filesystem;
using namespace roadslam;
using Config = mrpt::config::CConfigFileBase;

namespace {

/// Loads \p cfg with the components that read a kind of ini and returns what they save.
using Reader = std::function<std::string(const Config&)>;

std::string mapJob(const Config& cfg) { return jobs::effectiveMapConfig(cfg); }

std::string boundsJob(const Config& cfg) {  // what runBoundsJob reads
  boundary::Params bp;
  bp.loadFromConfigFile(cfg);
  odometry::Params op;
  op.loadFromConfigFile(cfg);
  velodyne::DecoderParams dp;
  dp.loadFromConfigFile(cfg, "velodyne");
  datasets::KittiParams kp;
  kp.loadFromConfigFile(cfg, "kitti");
  mrpt::config::CConfigFileMemory out;
  bp.saveToConfigFile(out);
  op.saveToConfigFile(out);
  dp.saveToConfigFile(out, "velodyne");
  kp.saveToConfigFile(out, "kitti");
  return out.getContent();
}

std::string preprocessPreset(const Config& cfg) {
  preprocess::PreprocessParams p;
  p.loadFromConfigFile(cfg, "preprocess");
  mrpt::config::CConfigFileMemory out;
  p.saveToConfigFile(out, "preprocess");
  return out.getContent();
}

std::string grab(const Config& cfg) {
  grabber::GrabParams p;
  p.loadFromConfigFile(cfg);
  mrpt::config::CConfigFileMemory out;
  p.saveToConfigFile(out);
  return out.getContent();
}

std::string scenario(const Config& cfg) {
  sim::ScenarioParams p;
  p.loadFromConfigFile(cfg);
  mrpt::config::CConfigFileMemory out;
  p.saveToConfigFile(out);
  return out.getContent();
}

std::string vehicleIni(const Config& cfg) {
  vehicle::VehicleParams p;
  p.loadFromConfigFile(cfg, "vehicle");
  mrpt::config::CConfigFileMemory out;
  p.saveToConfigFile(out, "vehicle");
  return out.getContent();
}

/// The reader of each shipped ini, by its path under ini/.
Reader readerOf(const std::string& rel) {
  static const std::map<std::string, Reader> kByName = {
      {"default.ini", mapJob},          {"kitti-hdl64.ini", mapJob},
      {"thesis-icp.ini", mapJob},       {"thesis-ndt.ini", mapJob},
      {"bounds.ini", boundsJob},        {"bounds-parking.ini", boundsJob},
      {"bounds-thesis.ini", boundsJob}, {"grab.ini", grab},
      {"grab-sim.ini", grab},
  };
  if (rel.rfind("sim/", 0) == 0) return scenario;
  if (rel.rfind("vehicles/", 0) == 0) return vehicleIni;
  if (rel.rfind("preprocess-", 0) == 0) return preprocessPreset;
  const auto it = kByName.find(rel);
  return it == kByName.end() ? Reader{} : it->second;
}

std::vector<std::string> shippedInis() {
  const fs::path root = fs::path(ROADSLAM_SOURCE_DIR) / "ini";
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(root))
    if (e.is_regular_file() && e.path().extension() == ".ini") out.push_back(fs::relative(e.path(), root).string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(ShippedInis, EveryOneRoundTripsThroughTheComponentThatReadsIt) {
  const auto inis = shippedInis();
  ASSERT_GE(inis.size(), 27u) << "ini/ has fewer files than shipped: is ROADSLAM_SOURCE_DIR right?";
  size_t sim = 0, vehicles = 0;
  for (const auto& rel : inis) {
    if (rel.rfind("experiments/", 0) == 0) continue;  // not a component's config: see below
    SCOPED_TRACE("ini/" + rel);
    const Reader read = readerOf(rel);
    ASSERT_TRUE(read) << "ini/" << rel << " has no reader in this test: add the component that loads it";
    const auto shipped = loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + rel);
    std::string first;
    ASSERT_NO_THROW(first = read(*shipped));
    EXPECT_NO_THROW(shipped->checkEntries(false)) << "a key of ini/" << rel << " is read by no component";
    ASSERT_FALSE(first.empty());
    std::string second;
    ASSERT_NO_THROW(second = read(mrpt::config::CConfigFileMemory(first)));
    EXPECT_EQ(first, second) << "ini/" << rel << ": the saved text does not load back to itself";
    sim += rel.rfind("sim/", 0) == 0;
    vehicles += rel.rfind("vehicles/", 0) == 0;
  }
  EXPECT_GE(sim, 9u);
  EXPECT_GE(vehicles, 6u);
}

// An experiment file is read by roadslam-experiment: every shipped one loads (its base configs, datasets
// and sweep keys checked, file:line on a problem) and plans datasets x configurations jobs.
TEST(ShippedInis, EveryExperimentLoadsAndPlans) {
  size_t n = 0;
  for (const auto& rel : shippedInis()) {
    if (rel.rfind("experiments/", 0) != 0) continue;
    SCOPED_TRACE("ini/" + rel);
    experiment::ExperimentSpec spec;
    ASSERT_NO_THROW(spec = experiment::loadExperiment(std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + rel));
    const auto configs = experiment::expandSweep(spec);
    EXPECT_GE(configs.size(), 2u) << "an experiment compares at least two configurations";
    const auto jobs = experiment::planJobs(spec, (fs::temp_directory_path() / "roadslam_plan_test").string());
    EXPECT_EQ(jobs.size(), configs.size() * spec.datasets.size());
    ++n;
  }
  EXPECT_GE(n, 3u) << "voxel-size, thesis-icp-vs-ndt, ground-removal";
}

// A section of a shipped config that knownSections() does not list is reported as unknown by every
// program that does not read it (roadslam-bounds or `roadslam-view --run-slam` on ini/default.ini
// stopped at a new [objects] section): the list and the shipped inis must agree.
TEST(ShippedInis, EverySectionIsAKnownSection) {
  for (const auto& rel : shippedInis()) {
    if (rel.rfind("experiments/", 0) == 0) continue;  // read by roadslam-experiment alone
    if (rel.rfind("grab", 0) == 0) continue;          // its sensor sections are named by its [grab] sensors
    const auto cfg = loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + rel);
    std::vector<std::string> sections;
    cfg->getAllSections(sections);
    for (const auto& s : sections) {
      EXPECT_NE(std::find(knownSections().begin(), knownSections().end(), s), knownSections().end())
          << "ini/" << rel << ": [" << s << "] is not in knownSections() (libs/common/src/checked_config.cpp)";
    }
  }
}
