// One source of defaults: an ini that leaves a key out gets the value ini/default.ini gives it, so a
// user's partial ini (a preset of a few keys) runs with the shipped defaults for the rest. Oracle:
// the shipped default.ini itself, key by key, against what the code does with an empty ini.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <map>
#include <sstream>
#include <vector>

#include "roadslam/common/config.h"
#include "roadslam/jobs/map_job.h"

using namespace roadslam;

namespace {

using Ini = std::map<std::string, std::string>;  // "section.key" -> value

Ini parse(const std::string& text) {
  Ini out;
  std::istringstream in(text);
  std::string line, section;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == ';' || line[0] == '#') continue;
    if (line[0] == '[') {
      section = line.substr(1, line.find(']') - 1);
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    auto trim = [](std::string s) {
      s.erase(0, s.find_first_not_of(" \t"));
      s.erase(s.find_last_not_of(" \t\r") + 1);
      return s;
    };
    out[section + "." + trim(line.substr(0, eq))] = trim(line.substr(eq + 1));
  }
  return out;
}

bool sameValue(const std::string& a, const std::string& b) {
  if (a == b) return true;
  char* ea = nullptr;
  char* eb = nullptr;
  const double x = std::strtod(a.c_str(), &ea), y = std::strtod(b.c_str(), &eb);
  return *ea == '\0' && *eb == '\0' && ea != a.c_str() && std::abs(x - y) <= 1e-9 * std::max(1.0, std::abs(x));
}

}  // namespace

TEST(Defaults, AnEmptyIniRunsWithTheShippedDefaults) {
  const mrpt::config::CConfigFileMemory empty;
  const auto shipped = loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini");
  const Ini code = parse(jobs::effectiveMapConfig(empty));
  const Ini ini = parse(jobs::effectiveMapConfig(*shipped));
  ASSERT_EQ(code.size(), ini.size());
  int differ = 0;
  for (const auto& [key, value] : ini) {
    EXPECT_TRUE(sameValue(code.at(key), value)) << key << ": code " << code.at(key) << ", default.ini " << value;
    differ += sameValue(code.at(key), value) ? 0 : 1;
  }
  std::cout << ini.size() << " keys compared, " << differ << " differ\n";
}

TEST(Defaults, EveryKeyTheShippedIniSetsIsAKeyTheCodeKnows) {
  // default.ini holds no key that no component reads (a typo there would hide behind a default)
  const Ini shipped = parse(*[] {
    std::ifstream f(std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini");
    return std::make_unique<std::string>((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  }());
  const Ini code = parse(jobs::effectiveMapConfig(mrpt::config::CConfigFileMemory()));
  for (const auto& [key, value] : shipped) EXPECT_TRUE(code.count(key)) << "default.ini sets " << key << ", which no component reads";
}

TEST(Defaults, DegreesAreWrittenBackAsGiven) {
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("odometry", "keyframe_angle_deg", 10);
  cfg.write("odometry", "gravity_kernel_deg", 2);
  const Ini used = parse(jobs::effectiveMapConfig(cfg));
  EXPECT_TRUE(sameValue(used.at("odometry.keyframe_angle_deg"), "10")) << used.at("odometry.keyframe_angle_deg");
  EXPECT_TRUE(sameValue(used.at("odometry.gravity_kernel_deg"), "2")) << used.at("odometry.gravity_kernel_deg");
  const Ini defaults = parse(jobs::effectiveMapConfig(mrpt::config::CConfigFileMemory()));
  EXPECT_TRUE(sameValue(defaults.at("odometry.keyframe_angle_deg"), "10")) << defaults.at("odometry.keyframe_angle_deg");
}

// ini/kitti-hdl64.ini is complete: the keys of ini/default.ini, every one, with the 64-beam sensor's
// own values only where its mounting differs.
TEST(Defaults, The64BeamConfigSetsEveryKeyOfTheDefaultOne) {
  const auto text = [](const std::string& name) {
    std::ifstream f(std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + name);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  };
  const Ini def = parse(text("default.ini")), k64 = parse(text("kitti-hdl64.ini"));
  ASSERT_GT(def.size(), 80u);
  std::vector<std::string> differ;
  for (const auto& [key, value] : def) {
    ASSERT_TRUE(k64.count(key)) << "ini/kitti-hdl64.ini lacks " << key;
    if (!sameValue(k64.at(key), value)) differ.push_back(key);
  }
  EXPECT_EQ(k64.size(), def.size());
  EXPECT_EQ(differ, (std::vector<std::string>{"grid.lidar_height_m", "preprocess.ego_radius_m", "preprocess.seg_sensor_height_m"}));
  const auto cfg = loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/kitti-hdl64.ini");
  EXPECT_NO_THROW(jobs::effectiveMapConfig(*cfg));
}

// Every shipped ini that roadslam-map takes is read whole: no key of it is unknown to the job.
TEST(Defaults, EveryShippedMapIniIsReadWhole) {
  for (const char* name : {"default.ini", "kitti-hdl64.ini", "thesis-icp.ini", "thesis-ndt.ini", "preprocess-kitti.ini",
                           "preprocess-thesis.ini", "preprocess-vlp16-ground-removal.ini"}) {
    const auto cfg = loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + name);
    jobs::effectiveMapConfig(*cfg);
    const auto bad = cfg->unknownEntries();
    EXPECT_TRUE(bad.empty()) << name << ": " << bad.front();
  }
}
