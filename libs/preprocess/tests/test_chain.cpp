#include "roadslam/common/config.h"
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/preprocess/chain.h"
#include "synthetic_scene.h"

#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <limits>

namespace fs = std::filesystem;
using namespace roadslam;
using namespace roadslam::preprocess;

namespace {
const std::string kIniDir = std::string(ROADSLAM_SOURCE_DIR) + "/ini/";

PreprocessParams loadIni(const std::string& name) {
  const auto cfg = loadIniFile(kIniDir + name);
  PreprocessParams p;
  p.loadFromConfigFile(*cfg, "preprocess");
  return p;
}
Scan streetSweep() { return fixtures::makeStreetSweep(fixtures::StreetScene{}).scan; }
}  // namespace

TEST(PreprocessChain, EveryShippedPresetLoadsAndRuns) {
  size_t count = 0;
  for (const auto& e : fs::directory_iterator(kIniDir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("preprocess-", 0) != 0 || e.path().extension() != ".ini") continue;
    ++count;
    const PreprocessParams p = loadIni(name);
    EXPECT_TRUE(p.unknown_keys.empty()) << name << ": " << p.unknown_keys.front();
    PreprocessChain chain(p);
    Scan s = streetSweep();
    const auto rep = chain.process(s);
    EXPECT_FALSE(rep.skipped) << name;
    EXPECT_GT(rep.points_out, 0u) << name;
    EXPECT_LT(rep.points_out, rep.points_in) << name;
  }
  EXPECT_GE(count, 3u);
}

TEST(PreprocessChain, ThesisKeysLoadAsTheirSiEquivalents) {
  const PreprocessParams p = loadIni("preprocess-thesis.ini");
  EXPECT_DOUBLE_EQ(p.ego.radius_m, 3.0);
  EXPECT_DOUBLE_EQ(p.roi.half_x_m, 30.0);
  EXPECT_DOUBLE_EQ(p.roi.half_y_m, 15.0);
  EXPECT_DOUBLE_EQ(p.ransac.max_distance_m, 0.2);
  EXPECT_NEAR(p.ransac.max_angle_rad, 10.0 * M_PI / 180.0, 1e-12);
  EXPECT_DOUBLE_EQ(p.random.keep_fraction, 0.25);
  EXPECT_EQ(p.keep_every_n_frames, 2);
  EXPECT_EQ(p.filters, (std::vector<std::string>{"ego", "roi", "ground_ransac", "random"}));
}

TEST(PreprocessChain, SaveLoadRoundTripAndUnknownKeys) {
  PreprocessParams p = loadIni("preprocess-vlp16-ground-removal.ini");
  EXPECT_DOUBLE_EQ(p.voxel.voxel_size_m, 0.2);
  EXPECT_DOUBLE_EQ(p.ground_seg.sensor_height_m, 1.8);
  mrpt::config::CConfigFileMemory mem;
  p.saveToConfigFile(mem, "pp");
  PreprocessParams q;
  q.loadFromConfigFile(mem, "pp");
  EXPECT_EQ(q.filters, p.filters);
  EXPECT_DOUBLE_EQ(q.roi.min_z_m, p.roi.min_z_m);
  EXPECT_NEAR(q.ransac.max_angle_rad, p.ransac.max_angle_rad, 1e-6);  // MRPT writes ~7 digits
  EXPECT_EQ(q.sor.k, p.sor.k);
  EXPECT_TRUE(q.unknown_keys.empty());
  mem.write("pp", "voxel_sise_m", std::string("0.3"));
  q.loadFromConfigFile(mem, "pp");
  EXPECT_EQ(q.unknown_keys, std::vector<std::string>{"voxel_sise_m"});
  mem.write("pp", "filters", std::string("ego,voxels"));
  EXPECT_THROW(q.loadFromConfigFile(mem, "pp"), std::runtime_error);
}

TEST(PreprocessChain, ReportCountsEveryStepAndFramesAreSkipped) {
  PreprocessParams p;
  p.filters = {"ego", "range", "voxel"};
  p.keep_every_n_frames = 3;
  PreprocessChain chain(p);
  for (int f = 0; f < 7; ++f) {
    Scan s = streetSweep();
    s.points[5].z = std::numeric_limits<float>::quiet_NaN();
    s.points[9].x = std::numeric_limits<float>::infinity();
    const size_t n0 = s.points.size();
    const auto rep = chain.process(s);
    EXPECT_EQ(rep.skipped, f % 3 != 0) << f;
    if (rep.skipped) {
      EXPECT_EQ(s.points.size(), n0);
      continue;
    }
    ASSERT_EQ(rep.steps.size(), 4u);
    EXPECT_EQ(rep.steps[0].name, "non_finite");
    EXPECT_EQ(rep.steps[0].removed, 2u);
    size_t removed = 0;
    for (size_t i = 0; i < rep.steps.size(); ++i) {
      removed += rep.steps[i].removed;
      if (i > 0) {
        EXPECT_EQ(rep.steps[i].points_in, rep.steps[i - 1].points_in - rep.steps[i - 1].removed);
      }
      EXPECT_GE(rep.steps[i].wall_time_s, 0.0);
    }
    EXPECT_EQ(rep.points_in - removed, rep.points_out);
    EXPECT_EQ(s.points.size(), rep.points_out);
  }
  const std::string text = formatTotals(chain.totals());
  EXPECT_NE(text.find("frames: 7 (4 skipped)"), std::string::npos) << text;
  EXPECT_NE(text.find("non_finite: "), std::string::npos) << text;
  EXPECT_NE(text.find(" 6 removed"), std::string::npos) << text;  // 2 per processed frame
  EXPECT_EQ(chain.totals().frames, 7u);
  EXPECT_EQ(chain.totals().skipped, 4u);
  EXPECT_EQ(chain.totals().steps[0].removed, 6u);
}

TEST(PreprocessChain, EmptyAllNanAndKittiSweep) {
  PreprocessParams p;
  p.filters = {"ego", "range", "roi", "ground_ransac", "ground_linefit", "random", "voxel", "sor"};
  PreprocessChain chain(p);
  Scan empty;
  EXPECT_EQ(chain.process(empty).points_out, 0u);
  Scan nans;
  nans.points.resize(100);
  for (auto& q : nans.points) q.y = std::numeric_limits<float>::quiet_NaN();
  const auto rep = chain.process(nans);
  EXPECT_EQ(rep.steps[0].removed, 100u);
  EXPECT_EQ(rep.points_out, 0u);
  const std::string path = std::string(ROADSLAM_SHARED_DATA) + "/kitti/odometry-00-first16/velodyne/000000.bin";
  if (!fs::exists(path)) GTEST_SKIP() << "missing " << path;
  PreprocessChain kitti(loadIni("preprocess-kitti.ini"));
  Scan s = datasets::readKittiBin(path);
  const auto r = kitti.process(s);
  EXPECT_EQ(r.points_in, 124668u);
  EXPECT_GT(r.points_out, 5000u);
  EXPECT_LT(r.points_out, 40000u);
  for (const auto& q : s.points) EXPECT_GE(std::hypot(q.x, q.y), 3.0 - 0.5) << "ego radius";
}
