// Params of the mapping: the shipped ini loads, save -> load is the identity, typos are named.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <fstream>

#include "roadslam/common/config.h"
#include "roadslam/mapping/map_outputs.h"
#include "roadslam/mapping/mapper.h"
#include "roadslam/mapping/pose_graph.h"

using namespace roadslam;
using namespace roadslam::mapping;

TEST(MappingParams, DefaultIniLoadsAndRoundTrips) {
  const auto cfg = loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini");
  MapperParams mp;
  MapOutputParams op;
  mp.loadFromConfigFile(*cfg);
  op.loadFromConfigFile(*cfg);
  EXPECT_DOUBLE_EQ(mp.loop.search_radius_m, 12.0);
  EXPECT_NEAR(mp.loop.consistency_rot_rad, 2 * M_PI / 180, 1e-12);
  EXPECT_EQ(mp.loop.coarse.method, registration::Method::Ndt);
  EXPECT_DOUBLE_EQ(op.octomap.free_max_range_m, 10.0);
  EXPECT_DOUBLE_EQ(op.grid.lidar_height_m, 1.9);

  mrpt::config::CConfigFileMemory mem;
  mp.saveToConfigFile(mem);
  op.saveToConfigFile(mem);
  MapperParams mp2;
  MapOutputParams op2;
  mp2.loadFromConfigFile(mem);
  op2.loadFromConfigFile(mem);
  EXPECT_DOUBLE_EQ(mp2.loop.consistency_rot_rad_per_m, mp.loop.consistency_rot_rad_per_m);
  EXPECT_DOUBLE_EQ(mp2.graph.odometry_sigma_r_rad, mp.graph.odometry_sigma_r_rad);
  EXPECT_EQ(mp2.loop.level_guess, mp.loop.level_guess);
  EXPECT_DOUBLE_EQ(mp2.loop.fine.max_correspondence_distance_m, 1.0);
  EXPECT_DOUBLE_EQ(op2.octomap.keyframe_spacing_m, op.octomap.keyframe_spacing_m);
  EXPECT_DOUBLE_EQ(op2.grid.max_height_m, op.grid.max_height_m);
  EXPECT_DOUBLE_EQ(op2.point_map.voxel_m, op.point_map.voxel_m);
}

TEST(MappingParams, UnknownAndBadKeysAreNamed) {
  mrpt::config::CConfigFileMemory mem;
  mem.write("loop_closure", "search_radius", std::string("10"));  // missing unit suffix
  MapperParams mp;
  try {
    mp.loadFromConfigFile(mem);
    FAIL() << "no exception";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("search_radius"), std::string::npos) << e.what();
  }
  mrpt::config::CConfigFileMemory bad;
  bad.write("octomap", "prob_hit", std::string("0.3"));
  OctoMapParams op;
  EXPECT_THROW(op.loadFromConfigFile(bad), std::runtime_error);
}

// The solver's ini key: [pose_graph] optimizer selects the solver from a file, defaults to the own
// solver, and an unknown value names the key and the file ([gnss_fusion] optimizer: libs/gnss_fusion's
// GnssFusionIni.OptimizerKeySelectsTheSolver).
TEST(MappingParams, OptimizerKeysSelectTheSolver) {
  const std::string path = std::string(ROADSLAM_BINARY_DIR) + "/test-out-optimizer-keys.ini";
  auto write = [&](const std::string& graph) { std::ofstream(path) << "[pose_graph]\noptimizer = " << graph << "\n"; };
  EXPECT_EQ(PoseGraphParams{}.optimizer, GraphOptimizer::Lm);
  write("ceres");
  PoseGraphParams g;
  g.loadFromConfigFile(*loadIniFile(path));
  EXPECT_EQ(g.optimizer, GraphOptimizer::Ceres);
  // saved as loaded (config_used.ini)
  mrpt::config::CConfigFileMemory mem;
  g.saveToConfigFile(mem);
  EXPECT_EQ(mem.read_string("pose_graph", "optimizer", ""), "ceres");
  write("lm");
  g.loadFromConfigFile(*loadIniFile(path));
  EXPECT_EQ(g.optimizer, GraphOptimizer::Lm);
  write("g2o");
  try {
    g.loadFromConfigFile(*loadIniFile(path));
    ADD_FAILURE() << "pose_graph: g2o accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("optimizer"), std::string::npos) << what;
    EXPECT_NE(what.find("g2o"), std::string::npos) << what;
  }
  std::filesystem::remove(path);
}
