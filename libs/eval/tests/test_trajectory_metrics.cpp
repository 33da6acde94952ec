#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "roadslam/eval/plot.h"
#include "roadslam/eval/trajectory_metrics.h"

using roadslam::datasets::PoseList;
using roadslam::datasets::Trajectory;
using namespace roadslam::eval;

namespace {

// A closed-ish curvy 3D path: x along a sine road, slowly climbing, heading along the tangent.
Trajectory curvyPath(int n, double step_m) {
  Trajectory t;
  for (int i = 0; i < n; ++i) {
    const double s = i * step_m;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(s, 10 * std::sin(s / 30.0), 0.01 * s);
    const double yaw = std::atan2(std::cos(s / 30.0) / 3.0, 1.0);
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    t.poses.push_back(T);
    t.stamps_s.push_back(100.0 + 0.1 * i);
  }
  return t;
}

Eigen::Isometry3d someTransform() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX())).toRotationMatrix();
  T.translation() = Eigen::Vector3d(5, -3, 2);
  return T;
}

}  // namespace

TEST(TrajectoryMetrics, IdenticalTrajectoriesHaveZeroError) {
  const auto gt = curvyPath(500, 0.5);
  const auto m = computeMetrics(associate(gt, gt));
  EXPECT_EQ(m.matched_poses, 500);
  EXPECT_NEAR(m.ate_rmse_m, 0, 1e-9);
  EXPECT_NEAR(m.rte_percent, 0, 1e-9);
  EXPECT_NEAR(m.rre_deg_per_100m, 0, 1e-6);
  EXPECT_NEAR(m.path_length_m, 249.5 * 1.0, 40.0);  // > straight length 249.5 m, curvy
}

TEST(TrajectoryMetrics, RigidlyMovedEstimateIsAlignedAway) {
  const auto gt = curvyPath(400, 0.5);
  Trajectory est = gt;
  const auto T = someTransform();
  for (auto& p : est.poses) p = T * p;
  const auto m = computeMetrics(associate(gt, est));
  EXPECT_NEAR(m.ate_rmse_m, 0, 1e-6);
  EXPECT_NEAR(m.ate_rmse_origin_aligned_m, 0, 1e-6);
  EXPECT_NEAR(m.rte_percent, 0, 1e-6);
  EXPECT_TRUE(m.T_gt_est.isApprox(T.inverse(), 1e-6));
}

TEST(TrajectoryMetrics, OnePercentScaleErrorGivesOnePercentRte) {
  // Straight line: a 1 % longer estimate is off by exactly 1 % of every segment length.
  Trajectory gt, est;
  for (int i = 0; i < 1000; ++i) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().x() = i * 1.0;
    gt.poses.push_back(T);
    T.translation().x() = i * 1.01;
    est.poses.push_back(T);
  }
  const auto m = computeMetrics(associate(gt, est));
  EXPECT_NEAR(m.rte_percent, 1.0, 1e-9);
  EXPECT_NEAR(m.rre_deg_per_100m, 0.0, 1e-9);
  ASSERT_EQ(m.per_length.size(), 8u);  // 999 m path: KITTI's 100..800 m lengths
  EXPECT_DOUBLE_EQ(m.per_length.front().length_m, 100.0);
  EXPECT_NEAR(m.final_position_error_m, 9.99, 1e-9);
}

TEST(TrajectoryMetrics, HeadingDriftGivesItsRateInDegPer100m) {
  // GT drives straight; the estimate's heading drifts 0.5 deg per 100 m of travel.
  const double drift_rad_per_m = 0.5 / 100.0 * M_PI / 180.0;
  Trajectory gt, est;
  for (int i = 0; i <= 300; ++i) {  // 300 m: segment lengths 30, 60, ... land on poses
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().x() = i * 1.0;
    gt.poses.push_back(T);
    T.linear() = Eigen::AngleAxisd(drift_rad_per_m * i, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    est.poses.push_back(T);
  }
  const auto m = computeMetrics(associate(gt, est));
  EXPECT_NEAR(m.rre_deg_per_100m, 0.5, 1e-6);
  ASSERT_EQ(m.per_length.size(), 9u);  // 300 m: 10 %..90 % of the path
  EXPECT_NEAR(m.per_length[0].length_m, 30.0, 1e-9);
}

TEST(TrajectoryMetrics, AssociationByTimeSkipsUnmatchedStamps) {
  const auto gt = curvyPath(100, 0.5);  // stamps 100.0 .. 109.9 every 0.1 s
  Trajectory est;
  for (int i = 0; i < 50; ++i) {
    est.stamps_s.push_back(100.0 + 0.2 * i + 0.004);  // 4 ms late, within tolerance
    est.poses.push_back(gt.poses[2 * i]);
  }
  est.stamps_s.push_back(200.0);  // no GT there
  est.poses.push_back(Eigen::Isometry3d::Identity());
  const auto m = associate(gt, est, 0.01);
  ASSERT_EQ(m.gt.size(), 50u);
  for (size_t i = 0; i < m.gt.size(); ++i) EXPECT_TRUE(m.gt[i].isApprox(m.est[i]));
}

TEST(TrajectoryMetrics, TooFewPosesIsAnError) {
  MatchedTrajectories m;
  m.gt.push_back(Eigen::Isometry3d::Identity());
  m.est.push_back(Eigen::Isometry3d::Identity());
  EXPECT_THROW(computeMetrics(m), std::invalid_argument);
}

TEST(Plot, WritesAPngOfTheRequestedSize) {
  const auto gt = curvyPath(300, 0.5);
  Trajectory est = gt;
  for (size_t i = 0; i < est.poses.size(); ++i) est.poses[i].translation().y() += 0.002 * i;
  const auto mt = associate(gt, est);
  const auto metrics = computeMetrics(mt);
  const auto path = std::filesystem::temp_directory_path() /
                    ("roadslam_plot_" + std::to_string(::getpid()) + ".png");
  plotTrajectories(path.string(), mt, metrics, "test");
  mrpt::img::CImage img;
  ASSERT_TRUE(img.loadFromFile(path.string()));
  EXPECT_EQ(img.getWidth(), 900u);
  EXPECT_EQ(img.getHeight(), 960u);
  std::filesystem::remove(path);
}
