#include "roadslam/datasets/kitti_scans.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "kitti_data.h"

namespace fs = std::filesystem;
using namespace roadslam;
using namespace roadslam::datasets;

namespace {
using roadslam::datasets::test::kOdo;

fs::path tempDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("roadslam_kitti_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

Scan syntheticScan(size_t n) {
  Scan s;
  for (size_t i = 0; i < n; ++i) {
    ScanPoint p;
    p.x = 0.5f * static_cast<float>(i);
    p.y = -1.25f * static_cast<float>(i);
    p.z = 1e-3f * static_cast<float>(i);
    p.intensity = static_cast<float>(i % 100) / 100.f;
    s.points.push_back(p);
  }
  return s;
}
}  // namespace

TEST(KittiScans, BinRoundTripAndRecordLayout) {
  const fs::path dir = tempDir("rt");
  const Scan s = syntheticScan(37);
  writeKittiBin((dir / "000000.bin").string(), s);
  EXPECT_EQ(fs::file_size(dir / "000000.bin"), 37u * 16u);
  // Independent of the reader: point 3's y is float index 13 (4 floats per record) in the file.
  std::ifstream in(dir / "000000.bin", std::ios::binary);
  char raw[16 * 4];
  in.read(raw, sizeof(raw));
  float y3 = 0;
  std::memcpy(&y3, raw + 13 * 4, 4);
  EXPECT_EQ(y3, -3.75f);
  const Scan back = readKittiBin((dir / "000000.bin").string(), 12.5);
  ASSERT_EQ(back.points.size(), 37u);
  EXPECT_EQ(back.stamp_s, 12.5);
  EXPECT_FALSE(back.has_point_times);
  EXPECT_FALSE(back.has_rings);
  for (size_t i = 0; i < 37; ++i) {
    EXPECT_EQ(back.points[i].x, s.points[i].x);
    EXPECT_EQ(back.points[i].y, s.points[i].y);
    EXPECT_EQ(back.points[i].z, s.points[i].z);
    EXPECT_EQ(back.points[i].intensity, s.points[i].intensity);
  }
}

TEST(KittiScans, BadSizeNamesTheFile) {
  const fs::path dir = tempDir("bad");
  const std::string path = (dir / "000000.bin").string();
  std::ofstream(path, std::ios::binary) << std::string(17, 'x');
  try {
    readKittiBin(path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("multiple of 16"), std::string::npos) << e.what();
  }
  EXPECT_THROW(readKittiBin((dir / "missing.bin").string()), std::runtime_error);
  writeKittiBin((dir / "empty.bin").string(), Scan{});
  EXPECT_TRUE(readKittiBin((dir / "empty.bin").string()).points.empty());  // 0 bytes is a valid sweep
}

TEST(KittiScans, FolderOrderAndTimesBesideOrOneLevelUp) {
  const fs::path seq = tempDir("seq");
  fs::create_directories(seq / "velodyne");
  for (int i : {2, 0, 1}) {
    char name[16];
    std::snprintf(name, sizeof(name), "%06d.bin", i);
    writeKittiBin((seq / "velodyne" / name).string(), syntheticScan(static_cast<size_t>(i + 1)));
  }
  KittiScanFolder no_times((seq / "velodyne").string());
  EXPECT_FALSE(no_times.hasTimes());
  EXPECT_DOUBLE_EQ(no_times.stamp(2), 0.2);
  std::ofstream(seq / "times.txt") << "0.0\n0.11\n0.205\n";
  KittiScanFolder up((seq / "velodyne").string());
  ASSERT_EQ(up.size(), 3u);
  EXPECT_DOUBLE_EQ(up.stamp(1), 0.11);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(up.read(i).points.size(), i + 1);
  // the stamps are mid-sweep (KittiParams): a sweep's first firing is half a period earlier
  EXPECT_DOUBLE_EQ(up.read(2).stamp_s, 0.205 - 0.05);
  EXPECT_TRUE(up.read(2).times_from_azimuth);
  std::ofstream(seq / "velodyne" / "times.txt") << "5\n6\n";
  EXPECT_THROW(KittiScanFolder((seq / "velodyne").string()), std::runtime_error);  // count mismatch
  EXPECT_THROW(KittiScanFolder((seq / "nope").string()), std::runtime_error);
}

// Point counts and values read from the file bytes with Python's struct.unpack('<4f'), and the
// MANIFEST's range 120,295 - 124,668 points per scan.
TEST(KittiScans, Odometry00First16) {
  if (!fs::exists(kOdo + "velodyne/000000.bin")) GTEST_SKIP() << "missing " << kOdo << "velodyne/000000.bin";
  const size_t expected[16] = {124668, 124605, 124478, 124167, 123969, 123924, 123373, 122765,
                               122123, 121357, 121018, 120945, 120503, 120295, 120406, 121023};
  KittiParams as_stored;  // the file's values: no elevation correction, no time estimate
  as_stored.times_from_azimuth = false;
  as_stored.elevation_correction_rad = 0;
  KittiScanFolder folder(kOdo + "velodyne", kOdo + "times_first16.txt", as_stored);
  ASSERT_EQ(folder.size(), 16u);
  for (size_t i = 0; i < 16; ++i) EXPECT_EQ(folder.read(i).points.size(), expected[i]) << i;
  const Scan s0 = folder.read(0);
  EXPECT_EQ(s0.points[0].x, 52.89794158935547f);
  EXPECT_EQ(s0.points[0].y, 0.02298973873257637f);
  EXPECT_EQ(s0.points[0].z, 1.9979945421218872f);
  EXPECT_EQ(s0.points[0].intensity, 0.07999999821186066f);
  EXPECT_EQ(s0.points.back().x, 4.0923752784729f);
  EXPECT_EQ(s0.points.back().z, -1.8955610990524292f);
  const Scan s15 = folder.read(15);
  EXPECT_EQ(s15.points[0].y, 8.241253852844238f);
  EXPECT_NEAR(s15.stamp_s, 1.555212, 1e-9);
}

// The defaults: times from the azimuth (clockwise, cut behind, stamp = when facing forward) and
// the elevation raised by 0.22 deg with range and azimuth kept, against the file's own values.
TEST(KittiScans, TimedAndElevationCorrectedByDefault) {
  if (!fs::exists(kOdo + "velodyne/000000.bin")) GTEST_SKIP() << "missing " << kOdo << "velodyne/000000.bin";
  const KittiScanFolder folder(kOdo + "velodyne", kOdo + "times_first16.txt");
  const Scan raw = readKittiBin(folder.path(3), folder.stamp(3));
  const Scan s = folder.read(3);
  ASSERT_EQ(s.points.size(), raw.points.size());
  EXPECT_NEAR(s.stamp_s, folder.stamp(3) - 0.05, 1e-12);
  ASSERT_TRUE(s.has_point_times);
  for (size_t i = 0; i < s.points.size(); i += 997) {
    const auto& p = s.points[i];
    const auto& q = raw.points[i];
    const double az = std::atan2(q.y, q.x), el = std::atan2(q.z, std::hypot(q.x, q.y));
    EXPECT_NEAR(std::atan2(p.y, p.x), az, 1e-5);
    EXPECT_NEAR(std::atan2(p.z, std::hypot(p.x, p.y)), el + 0.22 * M_PI / 180, 1e-5);
    EXPECT_NEAR(std::hypot(p.x, p.y, p.z), std::hypot(q.x, q.y, q.z), 1e-4);
    // behind the car (az = +-180 deg) the sweep starts and ends, facing forward is its middle
    const double expected_t = 0.05 * (1.0 - az / M_PI);
    EXPECT_NEAR(p.t, expected_t, 1e-6) << "azimuth " << az * 180 / M_PI;
  }
}
