#include "roadslam/datasets/kitti_scans.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "kitti_data.h"

namespace fs = std::filesystem;
using namespace roadslam::datasets;

namespace {
using roadslam::datasets::test::kRaw;

/// num_points column of oxts_vehicle_pose.csv: counted by the XVIZ converter, not by our reader.
std::vector<size_t> pointCountsFromCsv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  std::vector<size_t> counts;
  while (std::getline(in, line)) counts.push_back(std::stoul(line.substr(line.rfind(',') + 1)));
  return counts;
}
}  // namespace

// Unpacks velodyne.tar.zst once into the build tree (shared by every test that needs the drive).
TEST(KittiRawDrive, UnpackedSweepsMatchTheOxtsPointCounts) {
  if (!fs::exists(kRaw + "velodyne.tar.zst")) GTEST_SKIP() << "missing " << kRaw << "velodyne.tar.zst";
  // Same folder as the odometry tests use, so the suite unpacks the 190 MB only once.
  const std::string cache = std::string(ROADSLAM_BINARY_DIR) + "/data/kitti-raw-0001";
  unpackTarZstOnce(kRaw + "velodyne.tar.zst", cache);
  EXPECT_TRUE(fs::exists(cache + "/.unpacked"));
  unpackTarZstOnce(kRaw + "velodyne.tar.zst", cache);  // second call: no-op
  KittiScanFolder folder(cache + "/velodyne", kRaw + "times.txt");
  ASSERT_EQ(folder.size(), 108u);
  EXPECT_NEAR(folder.stamp(107), 11.04, 1e-9);
  const auto counts = pointCountsFromCsv(kRaw + "oxts_vehicle_pose.csv");
  ASSERT_EQ(counts.size(), 108u);
  for (size_t i = 0; i < 108; i += 1) {
    EXPECT_EQ(fs::file_size(folder.path(i)), 16 * counts[i]) << folder.path(i);
  }
  for (size_t i : {size_t{0}, size_t{53}, size_t{107}}) {
    EXPECT_EQ(folder.read(i).points.size(), counts[i]) << i;
  }
}
