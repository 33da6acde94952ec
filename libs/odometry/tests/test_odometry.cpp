#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <unordered_map>

#include "roadslam/common/voxel_hash.h"
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

namespace {

// Reference for the forward motion between two sweeps, independent of the registration code: the
// shift along x that minimises the median nearest-neighbour distance of the second sweep's
// structures (off the road, 5-40 m) to the first's, by exhaustive search on a 1 cm grid.
double forwardShiftByExhaustiveSearch(const Scan& a, const Scan& b) {
  const double cell = 0.5;
  const auto key = [&](const Eigen::Vector3d& p) -> Eigen::Vector3i { return (p / cell).array().floor().cast<int>(); };
  const auto structures = [](const Scan& s, size_t step) {
    std::vector<Eigen::Vector3d> out;
    for (size_t i = 0; i < s.points.size(); i += step) {
      const auto& q = s.points[i];
      const double r = std::hypot(q.x, q.y);
      if (r > 5 && r < 40 && q.z > -1.3) out.emplace_back(q.x, q.y, q.z);
    }
    return out;
  };
  std::unordered_map<Eigen::Vector3i, std::vector<Eigen::Vector3d>, VoxelKeyHash> grid;
  for (const auto& p : structures(a, 1)) grid[key(p)].push_back(p);
  const auto query = structures(b, 5);
  double best_shift = 0, best_median = 1e9;
  for (double tx = 0.4; tx <= 1.2; tx += 0.01) {
    std::vector<double> d;
    for (const auto& q0 : query) {
      const Eigen::Vector3d q = q0 + Eigen::Vector3d(tx, 0, 0);
      const Eigen::Vector3i k = key(q);
      double best = 9;
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            const auto it = grid.find(k + Eigen::Vector3i(dx, dy, dz));
            if (it == grid.end()) continue;
            for (const auto& p : it->second) best = std::min(best, (p - q).squaredNorm());
          }
      d.push_back(best);
    }
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    if (d[d.size() / 2] < best_median) best_median = d[d.size() / 2], best_shift = tx;
  }
  return best_shift;
}

}  // namespace

// KITTI odometry 00, its first 16 sweeps (12.9 m straight ahead), against KITTI's reference poses
// moved into the velodyne frame through calib.txt's Tr. The reference drives a constant 0.859 m per
// sweep; the sweeps themselves say the car accelerates from about 0.68 to 0.86 m per sweep (the
// exhaustive search above, and our odometry, agree within centimetres), so the ATE against the
// reference is mostly the reference's own start: it is printed, and the motions are checked
// against the sweeps.
TEST(Odometry, KittiOdometry00First16AgainstGroundTruthAndTheSweeps) {
  const std::string dir = kData + "/kitti/odometry-00-first16/";
  if (!fs::exists(dir + "velodyne/000015.bin")) GTEST_SKIP() << "missing " << dir << "velodyne/000015.bin";
  const datasets::KittiScanFolder folder(dir + "velodyne", dir + "times_first16.txt");
  const auto cam = datasets::readKittiTrajectory(dir + "poses_first16.txt", dir + "times_first16.txt");
  const auto gt = datasets::cameraPosesToVelodyne(cam.poses, datasets::readKittiOdometryCalib(dir + "calib.txt").T_cam0_velo);
  ASSERT_EQ(folder.size(), gt.size());
  odometry::Odometry odo(kittiParams());
  eval::MatchedTrajectories m;
  for (size_t i = 0; i < folder.size(); ++i) {
    const auto r = odo.process(folder.read(i));
    ASSERT_NE(r.status, odometry::FrameStatus::NotConverged) << "frame " << i << ": " << r.reason;
    m.gt.push_back(gt[i]);
    m.est.push_back(r.T_world_lidar);
  }
  const auto metrics = eval::computeMetrics(m);
  std::cout << "KITTI odometry 00 first 16 against the reference: ATE " << metrics.ate_rmse_m << " m, RTE "
            << metrics.rte_percent << " % (measured 0.37 m, 13 %: the reference's start, see above)\n";
  for (size_t i : {0u, 7u, 14u}) {
    const double ours = (m.est[i].inverse() * m.est[i + 1]).translation().x();
    const double reference = (gt[i].inverse() * gt[i + 1]).translation().x();
    const double sweeps = forwardShiftByExhaustiveSearch(folder.read(i), folder.read(i + 1));
    std::cout << "sweep " << i << " -> " << i + 1 << ": ours " << ours << " m, exhaustive search " << sweeps
              << " m, KITTI reference " << reference << " m\n";
    EXPECT_NEAR(ours, sweeps, 0.03);
  }
  EXPECT_LT(metrics.ate_rmse_m, 0.5);
}
