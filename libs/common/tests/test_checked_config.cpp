// Keys nobody reads are reported with file, line and the nearest key that was read; another
// program's sections pass; unknown sections are named with the nearest known one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "roadslam/common/config.h"

using namespace roadslam;

namespace {
std::string writeIni(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / ("roadslam-checked-" + std::to_string(::getpid()) + name);
  std::ofstream(p) << text;
  return p.string();
}
}  // namespace

TEST(CheckedConfig, TyposAreNamedWithLineAndNearestKey) {
  const std::string path = writeIni("a.ini",
                                    "; comment\n[odometry]\nvoxel_size_m = 0.5\nvoxel_sise_m = 0.7\n\n"
                                    "[octomap]\nresolution_m = 0.2\n[odometri]\nmap_radius_m = 3\n");
  const auto cfg = loadIniFile(path);
  EXPECT_DOUBLE_EQ(readDouble(*cfg, "odometry", "voxel_size_m", 1.0), 0.5);
  EXPECT_DOUBLE_EQ(readDouble(*cfg, "odometry", "map_radius_m", 80.0), 80.0);  // read, absent
  const auto bad = cfg->unknownEntries();
  ASSERT_EQ(bad.size(), 2u) << (bad.empty() ? "" : bad[0]);
  EXPECT_EQ(bad[0], path + ":4: unknown key 'voxel_sise_m' in [odometry] (nearest known: voxel_size_m)");
  EXPECT_EQ(bad[1], path + ":8: unknown section [odometri] (nearest known: [odometry])");
  // [octomap] is another program's section: not read here, not reported
  EXPECT_THROW(cfg->checkEntries(false), std::runtime_error);
  EXPECT_EQ(cfg->checkEntries(true).size(), 2u);
  std::filesystem::remove(path);
}

TEST(CheckedConfig, AFullyReadFileIsClean) {
  const std::string path = writeIni("b.ini", "[odometry]\nDeskew = true\n");
  const auto cfg = loadIniFile(path);
  EXPECT_TRUE(readBool(*cfg, "odometry", "deskew", false));  // ini keys are case-insensitive
  EXPECT_TRUE(cfg->unknownEntries().empty());
  EXPECT_NO_THROW(cfg->checkEntries(false));
  std::filesystem::remove(path);
}

TEST(CheckedConfig, EditDistance) {
  EXPECT_EQ(editDistance("voxel_sise_m", "voxel_size_m"), 1u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(editDistance("ABC", "abc"), 0u);
  EXPECT_EQ(editDistance("curb_heigth_m", "curb_height_m"), 1u);
}
