#include "roadslam/datasets/trajectory_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "kitti_data.h"

namespace fs = std::filesystem;
using namespace roadslam::datasets;

namespace {
using roadslam::datasets::test::kOdo;
using roadslam::datasets::test::kRaw;

std::string tempFile(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("roadslam_datasets_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return (dir / name).string();
}

PoseList randomPoses(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  PoseList poses;
  for (size_t i = 0; i < n; ++i) {
    Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng));
    poses.push_back(T);
  }
  return poses;
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(TrajectoryIo, TumRoundTrip) {
  Trajectory traj;
  traj.poses = randomPoses(50, 42);
  for (size_t i = 0; i < traj.poses.size(); ++i) traj.stamps_s.push_back(1.7e9 + 0.1 * i);
  const std::string path = tempFile("rt.tum");
  writeTum(path, traj);
  const Trajectory back = readTum(path);
  ASSERT_EQ(back.poses.size(), traj.poses.size());
  for (size_t i = 0; i < traj.poses.size(); ++i) {
    EXPECT_NEAR(back.stamps_s[i], traj.stamps_s[i], 1e-6);
    EXPECT_TRUE(back.poses[i].matrix().isApprox(traj.poses[i].matrix(), 1e-8)) << i;
  }
}

TEST(TrajectoryIo, KittiRoundTripWithTimes) {
  const PoseList poses = randomPoses(30, 7);
  std::vector<double> t;
  for (size_t i = 0; i < poses.size(); ++i) t.push_back(0.1037 * i);
  const std::string pp = tempFile("rt_poses.txt"), tp = tempFile("rt_times.txt");
  writeKittiPoses(pp, poses);
  writeTimes(tp, t);
  const Trajectory back = readKittiTrajectory(pp, tp);
  ASSERT_EQ(back.poses.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(back.stamps_s[i], t[i], 1e-9);
    EXPECT_TRUE(back.poses[i].matrix().isApprox(poses[i].matrix(), 1e-9)) << i;
  }
}

TEST(TrajectoryIo, MalformedLinesNameFileAndLine) {
  const std::string tum = tempFile("bad.tum");
  writeText(tum, "# header\n0 1 2 3 0 0 0 1\n1 1 2 3 0 0 1\n");
  EXPECT_NE(errorOf([&] { readTum(tum); }).find(tum + ":3"), std::string::npos);
  const std::string kit = tempFile("bad_kitti.txt");
  writeText(kit, "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 x 0 0 1 0\n");
  EXPECT_NE(errorOf([&] { readKittiPoses(kit); }).find(kit + ":2"), std::string::npos);
  const std::string times = tempFile("bad_times.txt");
  writeText(times, "0.0\n0.1\n");
  EXPECT_NE(errorOf([&] { readKittiTrajectory(kit, times); }), "");
  EXPECT_NE(errorOf([&] { readTum(tempFile("does_not_exist.tum")); }).find("does_not_exist"),
            std::string::npos);
}

// MANIFEST of odometry-00-first16: 16 scans over 1.55 s, the car drives ~12.9 m straight ahead,
// ~0.86 m per frame; in the velodyne frame forward is +x.
TEST(TrajectoryIo, KittiOdometryGroundTruthToVelodyneFrame) {
  if (!fs::exists(kOdo + "poses_first16.txt")) GTEST_SKIP() << "missing " << kOdo << "poses_first16.txt";
  const Trajectory cam = readKittiTrajectory(kOdo + "poses_first16.txt", kOdo + "times_first16.txt");
  ASSERT_EQ(cam.poses.size(), 16u);
  EXPECT_NEAR(cam.stamps_s.back(), 1.555212, 1e-9);
  const KittiOdometryCalib calib = readKittiOdometryCalib(kOdo + "calib.txt");
  EXPECT_NEAR(calib.P[0](0, 0), 718.856, 1e-9);
  EXPECT_NEAR(calib.T_cam0_velo.translation().z(), -0.2921968648686, 1e-12);
  const PoseList velo = cameraPosesToVelodyne(cam.poses, calib.T_cam0_velo);
  EXPECT_TRUE(velo.front().matrix().isIdentity(1e-6));
  EXPECT_NEAR(pathLength(velo), 12.9, 0.1);
  const Eigen::Vector3d t_end = velo.back().translation();
  EXPECT_GT(t_end.x(), 12.5);
  EXPECT_LT(std::abs(t_end.y()), 1.0);  // GT: 0.70 m to the left over 12.9 m (cam x = -0.047 m/frame)
  EXPECT_LT(std::abs(t_end.z()), 0.5);
  // Frame change preserves motion magnitudes: camera z (forward) maps to velodyne x.
  EXPECT_NEAR(t_end.norm(), cam.poses.back().translation().norm(), 0.05);
  EXPECT_NEAR((velo[1].translation() - velo[0].translation()).norm(), 0.86, 0.02);
}

// MANIFEST of raw-2011_09_26-0001: 108 LiDAR-frame poses over 11.04 s, 106.9 m driven.
TEST(TrajectoryIo, KittiRawDrivePoses) {
  if (!fs::exists(kRaw + "poses_velo_kitti.txt")) GTEST_SKIP() << "missing " << kRaw << "poses_velo_kitti.txt";
  const Trajectory traj = readKittiTrajectory(kRaw + "poses_velo_kitti.txt", kRaw + "times.txt");
  ASSERT_EQ(traj.poses.size(), 108u);
  EXPECT_DOUBLE_EQ(traj.stamps_s.front(), 0.0);
  EXPECT_NEAR(traj.stamps_s.back(), 11.04, 1e-9);
  EXPECT_NEAR(pathLength(traj.poses), 106.9, 0.5);
  const Eigen::Isometry3d T_velo_imu = readKittiRawCalibImuToVelo(kRaw + "calib_imu_to_velo.txt");
  EXPECT_NEAR(T_velo_imu.translation().x(), -0.8086759, 1e-9);
  EXPECT_NEAR(T_velo_imu.linear().determinant(), 1.0, 1e-5);
  // poses_imu_kitti.txt and poses_velo_kitti.txt describe one motion in two frames (MANIFEST):
  // T_w_velo = inv(T_imu_velo(0)) * T_w_imu * T_imu_velo, world = first frame of each.
  const PoseList imu = readKittiPoses(kRaw + "poses_imu_kitti.txt");
  ASSERT_EQ(imu.size(), 108u);
  const Eigen::Isometry3d T_imu_velo = T_velo_imu.inverse();
  const Eigen::Isometry3d T0 = (imu.front() * T_imu_velo).inverse();
  for (size_t i = 0; i < imu.size(); i += 17) {
    const Eigen::Isometry3d expect = T0 * imu[i] * T_imu_velo;
    EXPECT_LT((expect.translation() - traj.poses[i].translation()).norm(), 1e-3) << i;
  }
}

// Epoch stamps (~1.7e9 s) keep their microseconds through every stamp writer: times.txt and TUM.
TEST(TrajectoryIo, EpochStampsSurviveWriteAndRead) {
  const std::vector<double> t = {1700000000.123456, 1700000000.223457, 1700000001.000001, 1699999999.999999};
  const std::string tp = tempFile("epoch_times.txt");
  writeTimes(tp, t);
  const auto back = readTimes(tp);
  ASSERT_EQ(back.size(), t.size());
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(back[i], t[i], 1e-6) << i;

  Trajectory traj;
  traj.stamps_s = t;
  traj.poses = randomPoses(t.size(), 3);
  const std::string tum = tempFile("epoch.tum");
  writeTum(tum, traj);
  const auto tb = readTum(tum);
  ASSERT_EQ(tb.stamps_s.size(), t.size());
  for (size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(tb.stamps_s[i], t[i], 1e-6) << i;
}
