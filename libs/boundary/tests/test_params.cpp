#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include "roadslam/boundary/params.h"
#include "roadslam/common/config.h"

using roadslam::boundary::Params;

TEST(Params, ShippedInisLoad) {
  for (const char* name : {"bounds.ini", "bounds-thesis.ini", "bounds-parking.ini"}) {
    const auto cfg = roadslam::loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + name);
    Params p;
    ASSERT_NO_THROW(p.loadFromConfigFile(*cfg)) << name;
    EXPECT_DOUBLE_EQ(p.ground.sensor_height_m, 1.9) << name;
  }
  const auto thesis = roadslam::loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/bounds-thesis.ini");
  Params p;
  p.loadFromConfigFile(*thesis);
  EXPECT_EQ(p.method, roadslam::boundary::Method::Thesis);
  // The rules against parked cars read as curbs: off in bounds.ini, on in bounds-parking.ini.
  Params off, on;
  off.loadFromConfigFile(*roadslam::loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/bounds.ini"));
  on.loadFromConfigFile(*roadslam::loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/bounds-parking.ini"));
  EXPECT_EQ(off.curb_min_range_m, 0.0);
  EXPECT_EQ(off.curb_level_cells, 0);
  EXPECT_EQ(off.curb_veto_cells, -1);
  EXPECT_EQ(on.curb_min_range_m, 5.0);
  EXPECT_EQ(on.curb_level_cells, 5);
  EXPECT_EQ(on.curb_veto_cells, 2);
  EXPECT_EQ(on.method, off.method);
  EXPECT_EQ(on.ransac_seed, off.ransac_seed);
}

TEST(Params, SaveLoadRoundTrip) {
  Params a;
  a.method = roadslam::boundary::Method::Thesis;
  a.curb_min_jump_m = 0.07;
  a.memory_frames = 4;
  a.ground.max_slope = 0.2;
  mrpt::config::CConfigFileMemory mem;
  a.saveToConfigFile(mem);
  Params b;
  b.loadFromConfigFile(mem);
  EXPECT_EQ(b.method, roadslam::boundary::Method::Thesis);
  EXPECT_DOUBLE_EQ(b.curb_min_jump_m, 0.07);
  EXPECT_EQ(b.memory_frames, 4);
  EXPECT_DOUBLE_EQ(b.ground.max_slope, 0.2);
}

TEST(Params, BadKeysAreNamed) {
  mrpt::config::CConfigFileMemory mem;
  mem.write("boundary", "curb_min_jump", std::string("0.1"));
  Params p;
  try {
    p.loadFromConfigFile(mem);
    FAIL() << "unknown key accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("curb_min_jump"), std::string::npos) << e.what();
  }
  mrpt::config::CConfigFileMemory m2;
  m2.write("boundary", "method", std::string("magic"));
  try {
    p.loadFromConfigFile(m2);
    FAIL() << "unknown method accepted";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();  // names the key, the value and every valid method
    for (const char* w : {"method", "magic", "ransac", "thesis"}) EXPECT_NE(what.find(w), std::string::npos) << what;
  }
}
