// Global registration (FPFH + mutual matches + RANSAC + ICP) on synthetic inputs: descriptors are
// invariant to the pose, a scene moved far is found with no guess, degenerate inputs fail with a status.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roadslam/registration/global_registration.h>

#include <random>

#include "scene.h"

namespace roadslam::registration {
namespace {

Eigen::Isometry3d pose(double x, double y, double yaw_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() << x, y, 0.0;
  return T;
}

using test::transformed;

// Rusu 2009: a point's FPFH depends only on its neighbourhood's shape. Moving the cloud and the
// viewpoint together changes nothing but rounding.
TEST(Fpfh, InvariantToARigidMotion) {
  const PointCloud a = voxelDownsample(test::structuredScene(20, 0.01, 3), 1.0);
  const Eigen::Isometry3d T = pose(7, -4, 130);
  const PointCloud b = transformed(a, T);
  const PointCloud na = estimateNormals(a, 2.0, Eigen::Vector3d::Zero());
  const PointCloud nb = estimateNormals(b, 2.0, T.translation());
  std::vector<int> at;
  for (size_t i = 0; i < a.size(); ++i) at.push_back(static_cast<int>(i));
  const auto fa = computeFpfh(a, na, at, 5.0), fb = computeFpfh(b, nb, at, 5.0);
  // a pair feature lying on a bin edge may fall on either side after rounding: count the descriptors
  // that differ by more than 0.5 (of the 100 each group of bins sums to)
  int differ = 0, nonzero = 0;
  for (size_t i = 0; i < fa.size(); ++i) {
    differ += (fa[i] - fb[i]).cwiseAbs().maxCoeff() > 0.5f ? 1 : 0;
    nonzero += fa[i].sum() > 0 ? 1 : 0;
  }
  EXPECT_LE(differ, static_cast<int>(fa.size()) / 100) << "of " << fa.size();
  EXPECT_GT(nonzero, static_cast<int>(fa.size()) / 2);
}

// The structured scene (boxes, poles, facade) sampled twice independently, the source moved 12 m and
// turned 120 deg: no guess, recovered within 0.2 m / 1 deg by the ground-truth oracle.
TEST(GlobalRegistration, RecoversALargeOffsetWithNoGuess) {
  const Eigen::Isometry3d T_target_source = pose(12, -5, 120);
  const PointCloud target = test::structuredScene(30, 0.01, 1);
  const PointCloud source = transformed(test::structuredScene(30, 0.01, 2), T_target_source.inverse());
  GlobalParams prm;
  GlobalDiagnostics d;
  const RegistrationResult r = alignGlobal(target, source, prm, &d);
  ASSERT_TRUE(r.converged) << toString(r.status) << ": " << r.reason;
  const Eigen::Isometry3d E = T_target_source.inverse() * r.T_target_source;
  EXPECT_LT(E.translation().norm(), 0.2);
  EXPECT_LT(Eigen::AngleAxisd(E.linear()).angle() * 180 / M_PI, 1.0);
  EXPECT_GT(r.confidence, prm.min_confidence);
  EXPECT_GE(d.consensus, prm.min_consensus);
}

// Features cached per cloud (computeFeatures once, reused for many pairs; also with the caches dropped,
// as a FeatureCloud made by hand has none): the same pose and status as from the two clouds, and a cloud
// serves as target and source of different pairs.
TEST(GlobalRegistration, CachedFeaturesGiveTheSameResultAsTheClouds) {
  const Eigen::Isometry3d T_target_source = pose(12, -5, 120);
  const PointCloud target = test::structuredScene(30, 0.01, 1);
  const PointCloud source = transformed(test::structuredScene(30, 0.01, 2), T_target_source.inverse());
  GlobalParams prm;
  const RegistrationResult direct = alignGlobal(target, source, prm);
  ASSERT_TRUE(direct.converged) << direct.reason;
  const FeatureCloud ft = computeFeatures(target, prm), fs = computeFeatures(source, prm);
  ASSERT_TRUE(ft.index && ft.refine_target && fs.index && fs.refine_target);
  FeatureCloud bare_t = ft, bare_s = fs;
  bare_t.index.reset(), bare_t.refine_target.reset(), bare_s.index.reset(), bare_s.refine_target.reset();
  for (const FeatureCloud* pair : {&ft, static_cast<const FeatureCloud*>(&bare_t)}) {
    const RegistrationResult cached = alignGlobal(*pair, pair == &ft ? fs : bare_s, prm);
    EXPECT_EQ(cached.status, direct.status);
    EXPECT_TRUE(cached.T_target_source.isApprox(direct.T_target_source, 1e-12));
  }
  // the other way round, from the same caches: the inverse pose
  const RegistrationResult back = alignGlobal(fs, ft, prm);
  ASSERT_TRUE(back.converged) << back.reason;
  const Eigen::Isometry3d E = back.T_target_source * direct.T_target_source;
  EXPECT_LT(E.translation().norm(), 0.2);
  EXPECT_LT(Eigen::AngleAxisd(E.linear()).angle() * 180 / M_PI, 1.0);
}

TEST(GlobalRegistration, TooFewPointsFailWithAReason) {
  PointCloud few;
  for (int i = 0; i < 10; ++i) few.emplace_back(i, 0.5 * i, 1.0);
  const RegistrationResult r = alignGlobal(few, few, GlobalParams{});
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, Status::TooFewPoints);
  EXPECT_FALSE(r.reason.empty());
}

PointCloud flatGround(uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-30, 30);
  std::normal_distribution<double> n(0, 0.01);
  PointCloud pts;
  for (int i = 0; i < 20000; ++i) pts.emplace_back(u(rng), u(rng), -1.8 + n(rng));
  return pts;
}

// A featureless plane fixes nothing in x, y or yaw: never a pose, whether its points are keypoints or not.
TEST(GlobalRegistration, FeaturelessPlaneIsNeverConverged) {
  GlobalParams prm;
  const RegistrationResult r = alignGlobal(flatGround(1), flatGround(2), prm);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, Status::TooFewPoints) << r.reason;
  prm.level_normal_rad = 0;  // every point a keypoint: features all alike
  prm.min_keypoints = 1;
  const RegistrationResult r2 = alignGlobal(flatGround(1), flatGround(2), prm);
  EXPECT_FALSE(r2.converged) << "pose " << r2.T_target_source.translation().transpose();
  EXPECT_FALSE(r2.reason.empty());
  std::printf("plane with keypoints: %s (%s)\n", toString(r2.status).c_str(), r2.reason.c_str());
}

TEST(GlobalRegistration, ParamsRoundTripAndBadValues) {
  GlobalParams a;
  a.voxel_m = 0.8;
  a.rival_angle_rad = 0.3;
  a.fine.max_iterations = 12;
  mrpt::config::CConfigFileMemory cfg;
  a.saveToConfigFile(cfg);
  GlobalParams b;
  b.loadFromConfigFile(cfg);
  EXPECT_DOUBLE_EQ(b.voxel_m, 0.8);
  EXPECT_NEAR(b.rival_angle_rad, 0.3, 1e-6);
  EXPECT_EQ(b.fine.max_iterations, 12);
  cfg.write("global_registration", "edge_similarity", std::string("1.5"));
  EXPECT_THROW(b.loadFromConfigFile(cfg), std::runtime_error);
  mrpt::config::CConfigFileMemory bad;
  bad.write("global_registration", "voxel", std::string("1"));
  EXPECT_THROW(GlobalParams{}.loadFromConfigFile(bad), std::runtime_error);
}

}  // namespace
}  // namespace roadslam::registration
