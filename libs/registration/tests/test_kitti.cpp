// Oracle: consecutive KITTI odometry 00 sweeps register to the ground-truth relative motion
// (KITTI poses are left-camera poses; T_velo0_velo_i = Tr^-1 P_i Tr with Tr from calib.txt).
#include <gtest/gtest.h>
#include <roadslam/datasets/kitti_scans.h>
#include <roadslam/datasets/trajectory_io.h>
#include <roadslam/registration/registration.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace roadslam::registration {
namespace {
namespace ds = roadslam::datasets;

const std::string kSeq = std::string(ROADSLAM_SHARED_DATA) + "/kitti/odometry-00-first16/";
constexpr double kVoxel_m = 0.5;  // the odometry's source/target voxel size

struct Kitti00 {
  std::vector<PointCloud> clouds;  // voxelized, velodyne frame [m]
  ds::PoseList T_velo0_velo;
};

const Kitti00* kitti00() {
  static const Kitti00* d = []() -> const Kitti00* {
    if (!std::filesystem::exists(kSeq + "calib.txt")) return nullptr;
    auto* out = new Kitti00;
    const auto calib = ds::readKittiOdometryCalib(kSeq + "calib.txt");
    out->T_velo0_velo = ds::cameraPosesToVelodyne(ds::readKittiPoses(kSeq + "poses_first16.txt"), calib.T_cam0_velo);
    const ds::KittiScanFolder folder(kSeq + "velodyne");
    for (size_t i = 0; i < folder.size(); ++i) out->clouds.push_back(voxelDownsample(toPointCloud(folder.read(i)), kVoxel_m));
    return out;
  }();
  return d;
}

struct Errors {
  std::vector<double> terr_m, rerr_deg;
  int not_converged = 0;
  double weakest_eigenvalue = 1e9;  // smallest normalized Hessian eigenvalue seen [-]
  int num_weak = 0;                 // weak directions flagged over all pairs [-]
};

// Registers pair (i-1, i) for every i with guess(i); returns translation/rotation errors vs GT.
template <class Guess>
Errors registerPairs(const Kitti00& k, const Params& prm, Guess guess) {
  Errors e;
  for (size_t i = 1; i < k.clouds.size(); ++i) {
    const Eigen::Isometry3d gt = k.T_velo0_velo[i - 1].inverse() * k.T_velo0_velo[i];
    const Target target(k.clouds[i - 1], prm);
    const RegistrationResult r = align(target, k.clouds[i], guess(i), prm);
    const Eigen::Isometry3d E = gt.inverse() * r.T_target_source;
    e.terr_m.push_back(E.translation().norm());
    e.rerr_deg.push_back(Eigen::AngleAxisd(E.linear()).angle() * 180.0 / M_PI);
    e.not_converged += r.converged ? 0 : 1;
    e.weakest_eigenvalue = std::min(e.weakest_eigenvalue, r.degeneracy.eigenvalues(0));
    e.num_weak += r.degeneracy.num_weak;
    std::printf("  pair %2zu %-20s %-16s it %3d  terr %.3f m  rerr %.3f deg  inliers %d fitness %.3f weakest %.3f\n",
                i, toString(prm.method).c_str(), toString(r.status).c_str(), r.iterations, e.terr_m.back(),
                e.rerr_deg.back(), r.inliers, r.fitness, r.degeneracy.eigenvalues(0));
  }
  return e;
}

double maxOf(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }
double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

class KittiTest : public ::testing::TestWithParam<Method> {};

// As the odometry uses it: the previous pair's motion as initial guess (constant velocity).
TEST_P(KittiTest, ConsecutivePairsMatchGroundTruthWithConstantVelocityGuess) {
  const Kitti00* k = kitti00();
  if (!k) GTEST_SKIP() << "missing " << kSeq << "calib.txt";
  Params prm;
  prm.method = GetParam();
  const Errors e = registerPairs(*k, prm, [&](size_t i) {
    return i < 2 ? Eigen::Isometry3d::Identity() : k->T_velo0_velo[i - 2].inverse() * k->T_velo0_velo[i - 1];
  });
  // Measured (15 pairs, all three methods agree to ~2 cm): the estimate is shorter than the GT along
  // x by 17 cm on pair 1 shrinking to 2 cm by pair 15 at a constant GT speed of 8.6 m/s, the same for
  // every method, so the data (unde-skewed sweeps, KITTI GT) bounds it, not the solver. Maxima seen:
  // 0.216 m / 0.24 deg; medians 0.035 (p2p), 0.070 (p2pl), 0.075 (ndt) m. Thresholds with margin:
  EXPECT_LE(e.not_converged, GetParam() == Method::IcpPointToPoint ? 2 : 0);
  EXPECT_LT(maxOf(e.terr_m), 0.25);
  EXPECT_LT(maxOf(e.rerr_deg), 0.35);
  EXPECT_LT(median(e.terr_m), 0.10);
  // A city street constrains all six directions (weakest normalized eigenvalue measured: 0.063).
  EXPECT_EQ(e.num_weak, 0) << "weakest " << e.weakest_eigenvalue;
}

// KITTI raw drive 0001 with OXTS ground truth in the velodyne frame: the benchmark's setting
// (identity guess, motion up to 1.3 m per sweep) on the first 20 pairs.
TEST_P(KittiTest, RawDrivePairsFromIdentityGuess) {
  const std::string raw = std::string(ROADSLAM_SHARED_DATA) + "/kitti/raw-2011_09_26-0001/";
  if (!std::filesystem::exists(raw + "velodyne.tar.zst")) GTEST_SKIP() << "missing " << raw << "velodyne.tar.zst";
  const std::string cache =
      ds::unpackTarZstOnce(raw + "velodyne.tar.zst", std::string(ROADSLAM_BINARY_DIR) + "/data/kitti-raw-0001");
  const ds::KittiScanFolder folder(cache + "/velodyne");
  Kitti00 k;
  const ds::PoseList all = ds::readKittiPoses(raw + "poses_velo_kitti.txt");
  for (size_t i = 0; i <= 20; ++i) {
    k.clouds.push_back(voxelDownsample(toPointCloud(folder.read(i)), kVoxel_m));
    k.T_velo0_velo.push_back(all[i]);
  }
  Params prm;
  prm.method = GetParam();
  const bool p2p = prm.method == Method::IcpPointToPoint;
  if (p2p) {  // the documented point-to-point setting: Geman-McClure keeps it at identity here
    prm.kernel = Kernel::Huber;
    prm.kernel_scale_m = 1.0;
    prm.max_iterations = 100;
  }
  const Errors e = registerPairs(k, prm, [](size_t) { return Eigen::Isometry3d::Identity(); });
  // Measured here: max 0.087 (p2pl) / 0.098 (ndt) m, max 0.074 deg, medians 0.052 / 0.042 m.
  // Point-to-point slides along the ground in sub-0.5 mm steps and stops 0-25 cm short of the
  // motion: max 0.247 m, median 0.139 m, max 0.12 deg. It needs a motion prediction (see above).
  EXPECT_EQ(e.not_converged, 0);
  EXPECT_LT(maxOf(e.terr_m), p2p ? 0.35 : 0.15);
  EXPECT_LT(maxOf(e.rerr_deg), 0.2);
  EXPECT_LT(median(e.terr_m), p2p ? 0.2 : 0.07);
  EXPECT_EQ(e.num_weak, 0) << "weakest " << e.weakest_eigenvalue;
}

INSTANTIATE_TEST_SUITE_P(AllMethods, KittiTest,
                         ::testing::Values(Method::IcpPointToPoint, Method::IcpPointToPlane, Method::Ndt),
                         [](const auto& info) { return toString(info.param); });

}  // namespace
}  // namespace roadslam::registration
