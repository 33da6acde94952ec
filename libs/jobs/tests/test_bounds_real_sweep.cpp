// Real VLP-16 captures from ../shared/data/velodyne (static, indoors): labelling on regions that
// are certain from the geometry and the pictures, and the whole app job (odometry poses) producing
// its files. Skipped when a capture is absent.
//
// Hand-checked, VeloView capture vlp-16-test-90deg, third sweep (13,898 points; see the side views
// drawn while writing this test): the sensor stands level (ring 8 = +1 deg has z > 0 everywhere,
// ring 7 = -1 deg z < 0), and a flat ceiling 1.5 m above it spans x < -2 m (479 points within
// z 1.45-1.65 m). No floor is in view: the beams below the horizon end on furniture within 2 m.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "roadslam/boundary/detector.h"
#include "roadslam/jobs/bounds_job.h"
#include "roadslam/common/config.h"
#include "roadslam/sources/scan_source.h"

namespace fs = std::filesystem;
using namespace roadslam;

namespace {

const std::string kVeloView = std::string(ROADSLAM_SHARED_DATA) + "/velodyne/veloview_vlp-16-test-90deg-1-50-frames.pcap";
const std::string kMrpt = std::string(ROADSLAM_SHARED_DATA) + "/velodyne/mrpt_sample_velodyne_vlp16_gps.pcap";

std::optional<Scan> sweep(const std::string& path, int k) {
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("velodyne", "model", std::string("vlp16"));  // the VeloView capture reports 0x21
  auto s = sources::openScanSource(path, cfg);
  std::optional<Scan> out;
  for (int i = 0; i <= k; ++i) out = s->next();
  return out;
}

boundary::Params shippedParams() {
  boundary::Params p;
  p.loadFromConfigFile(*loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/bounds.ini"));
  return p;
}

}  // namespace

TEST(RealSweep, UpwardBeamsAndCeilingAreNeverGroundOrCurb) {
  if (!fs::exists(kVeloView)) GTEST_SKIP() << "absent: " << kVeloView;
  const auto s = sweep(kVeloView, 2);
  ASSERT_TRUE(s && s->has_rings);
  ASSERT_GT(s->points.size(), 13000u);
  const auto lab = boundary::labelPoints(*s, shippedParams());
  size_t up = 0, ceiling = 0;
  for (size_t i = 0; i < s->points.size(); ++i) {
    const auto& q = s->points[i];
    const bool bad = lab.cls[i] == boundary::PointClass::Ground || lab.cls[i] == boundary::PointClass::Curb;
    if (q.ring >= 8) {
      ++up;
      EXPECT_FALSE(bad) << "upward beam " << q.ring << " at z " << q.z;
    }
    if (q.x < -2 && q.z > 1.45 && q.z < 1.65) {
      ++ceiling;
      EXPECT_FALSE(bad) << "ceiling point at " << q.x << ", " << q.y;
    }
  }
  EXPECT_GT(up, 6000u);
  EXPECT_GT(ceiling, 300u);
}

TEST(RealSweep, NoFloorInViewIsReportedNotGuessed) {
  if (!fs::exists(kVeloView)) GTEST_SKIP() << "absent: " << kVeloView;
  boundary::BoundaryDetector det(shippedParams());
  const auto f = det.process(*sweep(kVeloView, 2), Eigen::Isometry3d::Identity(), 0.0);
  EXPECT_FALSE(f.left.found);
  EXPECT_FALSE(f.right.found);
  EXPECT_FALSE(f.left.reason.empty());
  EXPECT_FALSE(f.right.reason.empty());
}

TEST(RealSweep, AppJobWritesPicturesAndReasons) {
  for (const auto& path : {kVeloView, kMrpt}) {
    if (!fs::exists(path)) GTEST_SKIP() << "absent: " << path;
    jobs::BoundsRequest req;
    req.config_path = std::string(ROADSLAM_SOURCE_DIR) + "/ini/bounds.ini";
    req.input_path = path;
    req.out_dir = std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_real_" + fs::path(path).stem().string();
    req.png_every = 1;
    req.max_frames = 6;
    req.progress = false;
    const auto summary = jobs::runBoundsJob(req);
    EXPECT_GE(summary["frames"].get<int>(), 3) << path;
    EXPECT_TRUE(fs::exists(req.out_dir + "/top_view.png"));
    EXPECT_TRUE(fs::exists(req.out_dir + "/frames/000000.png"));
    std::ifstream f(req.out_dir + "/boundaries.jsonl");
    std::string line;
    int lines = 0;
    while (std::getline(f, line)) {
      ++lines;
      const auto j = nlohmann::json::parse(line);
      if (!j.contains("left")) continue;
      for (const char* side : {"left", "right"}) EXPECT_FALSE(j[side]["reason"].get<std::string>().empty());
    }
    EXPECT_EQ(lines, summary["frames"].get<int>() + summary["frames_without_pose"].get<int>());
  }
}
