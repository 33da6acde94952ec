#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/eval/trajectory_metrics.h"
#include "roadslam/odometry/odometry.h"

namespace fs = std::filesystem;
using namespace roadslam;

namespace {

const std::string kData = ROADSLAM_SHARED_DATA;

odometry::Params kittiParams() {
  odometry::Params p;
  p.preprocess.filters = {"range", "voxel"};
  p.preprocess.range.min_range_m = 5.0;
  p.preprocess.range.max_range_m = 100.0;
  p.preprocess.voxel.voxel_size_m = 0.5;
  p.registration.method = registration::Method::IcpPointToPlane;
  return p;
}

eval::TrajectoryMetrics runOnFolder(const datasets::KittiScanFolder& folder, const datasets::PoseList& gt,
                                    odometry::Params params) {
  odometry::Odometry odo(params);
  eval::MatchedTrajectories m;
  double ms = 0;
  for (size_t i = 0; i < folder.size(); ++i) {
    const auto r = odo.process(folder.read(i));
    ms += r.ms_total;
    EXPECT_NE(r.status, odometry::FrameStatus::NotConverged) << "frame " << i << ": " << r.reason;
    m.gt.push_back(gt[i]);
    m.est.push_back(r.T_world_lidar);
  }
  std::cout << "odometry " << ms / static_cast<double>(std::max<size_t>(folder.size(), 1))
            << " ms per sweep (reading excluded; a figure, not a bound)\n";
  return eval::computeMetrics(m);
}

}  // namespace

TEST(Odometry, KittiRawDriveAgainstOxtsGroundTruth) {
  const std::string dir = kData + "/kitti/raw-2011_09_26-0001";
  if (!fs::exists(dir + "/velodyne.tar.zst")) GTEST_SKIP() << "missing " << dir << "/velodyne.tar.zst";
  const std::string unpacked =
      datasets::unpackTarZstOnce(dir + "/velodyne.tar.zst", std::string(ROADSLAM_BINARY_DIR) + "/data/kitti-raw-0001");
  std::string scans = unpacked;
  for (auto& e : fs::recursive_directory_iterator(unpacked)) {
    if (e.path().extension() == ".bin") { scans = e.path().parent_path().string(); break; }
  }
  const datasets::KittiScanFolder folder(scans, dir + "/times.txt");
  const auto gt = datasets::readKittiPoses(dir + "/poses_velo_kitti.txt");
  ASSERT_EQ(folder.size(), gt.size());
  const auto m = runOnFolder(folder, gt, kittiParams());
  std::cout << "KITTI raw 0001: ATE " << m.ate_rmse_m << " m, RTE " << m.rte_percent << " %, RRE "
            << m.rre_deg_per_100m << " deg/100m\n";
  // measured 0.46 % and 0.052 m; KISS-ICP: 0.45-1.03 %, 0.14-0.30 m (the odometry issue)
  EXPECT_LT(m.rte_percent, 0.6);
  EXPECT_LT(m.ate_rmse_m, 0.14);
}
