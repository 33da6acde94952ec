#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include "roadslam/common/config.h"

TEST(Config, ReadsValuesAndDefaults) {
  mrpt::config::CConfigFileMemory cfg(std::string("[a]\nx = 2.5\nn = 7\nb = yes\ns = hi\n"));
  EXPECT_DOUBLE_EQ(roadslam::readDouble(cfg, "a", "x", 0), 2.5);
  EXPECT_DOUBLE_EQ(roadslam::readDouble(cfg, "a", "missing", -1), -1);
  EXPECT_EQ(roadslam::readInt(cfg, "a", "n", 0), 7);
  EXPECT_TRUE(roadslam::readBool(cfg, "a", "b", false));
  EXPECT_EQ(roadslam::readString(cfg, "a", "s", ""), "hi");
}

TEST(Config, MalformedValueNamesSectionAndKey) {
  mrpt::config::CConfigFileMemory cfg(std::string("[filters]\nmax_range_m = 12x\n"));
  try {
    roadslam::readDouble(cfg, "filters", "max_range_m", 0);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("[filters] max_range_m"), std::string::npos) << e.what();
  }
}

TEST(Config, UnknownKeysAreListed) {
  mrpt::config::CConfigFileMemory cfg(std::string("[s]\ngood = 1\ntypo_kye = 2\n"));
  const auto u = roadslam::unknownKeys(cfg, "s", {"good"});
  ASSERT_EQ(u.size(), 1u);
  EXPECT_EQ(u[0], "typo_kye");
}

TEST(Config, MissingFileThrowsNamingIt) {
  EXPECT_THROW(roadslam::loadIniFile("/no/such/file.ini"), std::runtime_error);
}
