#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <iostream>
#include <unordered_map>

#include "roadslam/common/config.h"
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
  p.preprocess.ground_seg.sensor_height_m = 1.73;  // KITTI's HDL-64E
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

namespace {

/// KITTI raw 2011_09_26_0001 (unpacked once into the build tree) and its OXTS poses, or nullopt.
struct RawDrive {
  std::string scans, times, poses;
};
std::optional<RawDrive> rawDrive0001() {
  const std::string dir = kData + "/kitti/raw-2011_09_26-0001";
  if (!fs::exists(dir + "/velodyne.tar.zst")) return std::nullopt;
  const std::string unpacked =
      datasets::unpackTarZstOnce(dir + "/velodyne.tar.zst", std::string(ROADSLAM_BINARY_DIR) + "/data/kitti-raw-0001");
  return RawDrive{unpacked + "/velodyne", dir + "/times.txt", dir + "/poses_velo_kitti.txt"};
}

/// Every \p stride-th sweep of the drive through the odometry, against the OXTS poses.
eval::TrajectoryMetrics runRawDrive(const RawDrive& d, const std::string& ini, size_t stride,
                                    size_t* not_converged = nullptr) {
  const auto cfg = loadIniFile(ini);
  odometry::Params params;
  params.loadFromConfigFile(*cfg);
  datasets::KittiParams kp;
  kp.loadFromConfigFile(*cfg);
  const datasets::KittiScanFolder folder(d.scans, d.times, kp);
  const auto gt = datasets::readKittiPoses(d.poses);
  EXPECT_EQ(folder.size(), gt.size());
  odometry::Odometry odo(params);
  eval::MatchedTrajectories m;
  size_t failed = 0;
  for (size_t i = 0; i < folder.size(); i += stride) {
    auto scan = folder.read(i);
    if (stride > 1) scan.stamp_s = 0.1 * static_cast<double>(i / stride);  // every stride-th sweep, 0.1 s apart
    const auto r = odo.process(std::move(scan));
    failed += r.status == odometry::FrameStatus::NotConverged ? 1 : 0;
    m.gt.push_back(gt[i]);
    m.est.push_back(r.T_world_lidar);
  }
  if (not_converged) *not_converged = failed;
  return eval::computeMetrics(m);
}

const std::string kKittiIni = std::string(ROADSLAM_SOURCE_DIR) + "/ini/kitti-hdl64.ini";

}  // namespace

TEST(Odometry, KittiRawDriveAgainstOxtsGroundTruth) {
  const auto drive = rawDrive0001();
  if (!drive) GTEST_SKIP() << "missing " << kData << "/kitti/raw-2011_09_26-0001/velodyne.tar.zst";
  const auto folder = datasets::KittiScanFolder(drive->scans, drive->times);
  const auto gt = datasets::readKittiPoses(drive->poses);
  ASSERT_EQ(folder.size(), gt.size());
  const auto m = runOnFolder(folder, gt, kittiParams());
  std::cout << "KITTI raw 0001: ATE " << m.ate_rmse_m << " m, RTE " << m.rte_percent << " %, RRE "
            << m.rre_deg_per_100m << " deg/100m\n";
  // deskewed with azimuth times, elevation corrected: measured 0.382 % / 0.087 m (the
  // target 0.40 %); before either, 0.46 % and 0.052 m (the 5 m crop and 0.5 m voxels of kittiParams())
  EXPECT_LT(m.rte_percent, 0.40);
  EXPECT_LT(m.ate_rmse_m, 0.10);
}

// The shipped 64-beam config: every frame deskewed, the target of 0.40 %.
TEST(Odometry, KittiRawDriveWithTheShipped64BeamConfig) {
  const auto drive = rawDrive0001();
  if (!drive) GTEST_SKIP() << "missing " << kData << "/kitti/raw-2011_09_26-0001/velodyne.tar.zst";
  size_t failed = 0;
  const auto m = runRawDrive(*drive, kKittiIni, 1, &failed);
  std::cout << "KITTI raw 0001, ini/kitti-hdl64.ini: ATE " << m.ate_rmse_m << " m, RTE " << m.rte_percent << " %\n";
  EXPECT_EQ(failed, 0u);
  EXPECT_LT(m.rte_percent, 0.40);
}

// A start at speed: every third sweep of the drive is a car leaving at 39 m/s (3.9 m per sweep),
// beyond the voxel map's reach from a standing guess. With the first motion searched, no frame is
// lost and the drive scores like the full one; without, the start's yaw error stays in every pose
// (measured 0.82 % against 6.6 %).
TEST(Odometry, KittiRawDriveStartingAtThreeTimesItsSpeed) {
  const auto drive = rawDrive0001();
  if (!drive) GTEST_SKIP() << "missing " << kData << "/kitti/raw-2011_09_26-0001/velodyne.tar.zst";
  size_t failed = 0;
  const auto with_search = runRawDrive(*drive, kKittiIni, 3, &failed);
  EXPECT_EQ(failed, 0u);
  const std::string off = std::string(ROADSLAM_BINARY_DIR) + "/test-out/kitti-no-first-motion-search.ini";
  fs::create_directories(fs::path(off).parent_path());
  std::ifstream in(kKittiIni);
  std::ofstream(off) << in.rdbuf() << "\n[odometry]\nfirst_motion_search = false\n";
  const auto without = runRawDrive(*drive, off, 3);
  std::cout << "every third sweep: RTE " << with_search.rte_percent << " % with the first motion searched, "
            << without.rte_percent << " % without\n";
  EXPECT_LT(with_search.rte_percent, 1.5);
  EXPECT_GT(without.rte_percent, 2 * with_search.rte_percent);
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
