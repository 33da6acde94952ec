// Oracle: global registration (no initial guess) of real KITTI raw sweeps about 10 m apart, against the
// OXTS ground truth in the velodyne frame (each converged pose within 0.2 m / 1 deg, a refusal allowed,
// docs/benchmarks.md: 100 % of 46 pairs); and the first pair with the source turned 90 deg and moved 6 m.
#include <gtest/gtest.h>
#include <roadslam/datasets/kitti_scans.h>
#include <roadslam/datasets/trajectory_io.h>
#include <roadslam/registration/global_registration.h>

#include <cstdio>
#include <filesystem>

namespace roadslam::registration {
namespace {
namespace ds = roadslam::datasets;

const std::string kRaw = std::string(ROADSLAM_SHARED_DATA) + "/kitti/raw-2011_09_26-0001/";

struct Error {
  double t_m, r_deg;
};
Error errorOf(const Eigen::Isometry3d& gt, const Eigen::Isometry3d& est) {
  const Eigen::Isometry3d E = gt.inverse() * est;
  return {E.translation().norm(), Eigen::AngleAxisd(E.linear()).angle() * 180 / M_PI};
}

TEST(GlobalRegistrationKitti, RawPairsTenMetresApartWithNoGuess) {
  if (!std::filesystem::exists(kRaw + "velodyne.tar.zst")) GTEST_SKIP() << "missing " << kRaw << "velodyne.tar.zst";
  const std::string cache =
      ds::unpackTarZstOnce(kRaw + "velodyne.tar.zst", std::string(ROADSLAM_BINARY_DIR) + "/data/kitti-raw-0001");
  const ds::KittiScanFolder folder(cache + "/velodyne");
  const ds::PoseList T_w = ds::readKittiPoses(kRaw + "poses_velo_kitti.txt");
  const GlobalParams prm;
  int pairs = 0, converged = 0;
  for (size_t i = 0; i + 1 < T_w.size() && pairs < 3; i += 35) {
    size_t j = i + 1;
    while (j + 1 < T_w.size() && (T_w[j].translation() - T_w[i].translation()).norm() < 9.5) ++j;
    const Eigen::Isometry3d gt = T_w[i].inverse() * T_w[j];
    const PointCloud target = toPointCloud(folder.read(i)), source = toPointCloud(folder.read(j));
    const RegistrationResult r = alignGlobal(target, source, prm);
    const Error e = errorOf(gt, r.T_target_source);
    std::printf("pair %zu-%zu (%.1f m): %s conf %.2f  err %.3f m %.3f deg\n", i, j, gt.translation().norm(),
                toString(r.status).c_str(), r.confidence, e.t_m, e.r_deg);
    // a pair may be refused (pair 70-81: a rival pose along the street has 81 % of the support), never wrong
    converged += r.converged ? 1 : 0;
    if (r.converged) {
      EXPECT_LT(e.t_m, 0.2);
      EXPECT_LT(e.r_deg, 1.0);
    } else {
      EXPECT_FALSE(r.reason.empty());
    }
    if (pairs == 0) {  // a large known offset: the source sweep turned 90 deg and moved 6 m sideways
      Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
      D.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      D.translation() << 0, 6, 0;
      PointCloud moved;
      for (const auto& p : source) moved.push_back(D * p);
      const RegistrationResult r2 = alignGlobal(target, moved, prm);
      const Error e2 = errorOf(gt * D.inverse(), r2.T_target_source);
      std::printf("  moved: %s conf %.2f  err %.3f m %.3f deg\n", toString(r2.status).c_str(), r2.confidence, e2.t_m, e2.r_deg);
      EXPECT_TRUE(r2.converged) << r2.reason;
      EXPECT_LT(e2.t_m, 0.2);
      EXPECT_LT(e2.r_deg, 1.0);
    }
    ++pairs;
  }
  EXPECT_EQ(pairs, 3);
  EXPECT_GE(converged, 2);
}

}  // namespace
}  // namespace roadslam::registration
