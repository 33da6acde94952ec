// Params of the GNSS fusion: [gnss_fusion] optimizer selects the solver from a file, defaults to the
// own solver, saves as loaded, and an unknown value names the key and the file.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <fstream>

#include "roadslam/common/config.h"
#include "roadslam/gnss_fusion/gnss_fusion.h"

using namespace roadslam;
using namespace roadslam::gnss_fusion;

TEST(GnssFusionIni, OptimizerKeySelectsTheSolver) {
  const std::string path = std::string(ROADSLAM_BINARY_DIR) + "/test-out-gnss-optimizer-key.ini";
  auto write = [&](const std::string& gnss) { std::ofstream(path) << "[gnss_fusion]\noptimizer = " << gnss << "\n"; };
  EXPECT_EQ(GnssFusionParams{}.optimizer, GnssOptimizer::GaussNewton);
  write("ceres");
  GnssFusionParams f;
  f.loadFromConfigFile(*loadIniFile(path));
  EXPECT_EQ(f.optimizer, GnssOptimizer::Ceres);
  // saved as loaded (config_used.ini)
  mrpt::config::CConfigFileMemory mem;
  f.saveToConfigFile(mem);
  EXPECT_EQ(mem.read_string("gnss_fusion", "optimizer", ""), "ceres");
  write("gauss_newton");
  f.loadFromConfigFile(*loadIniFile(path));
  EXPECT_EQ(f.optimizer, GnssOptimizer::GaussNewton);
  write("g2o");
  try {
    f.loadFromConfigFile(*loadIniFile(path));
    ADD_FAILURE() << "gnss_fusion: g2o accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("optimizer"), std::string::npos) << what;
    EXPECT_NE(what.find("g2o"), std::string::npos) << what;
  }
  std::filesystem::remove(path);
}
