// The hdl64 output folder read back with libs/datasets: the .bin sweeps are the simulated points,
// times.txt the forward-facing stamps, poses_velo_kitti.txt the ground-truth lidar poses in the
// first sweep's frame; a plain VLP-16 ini with the new keys at 0 still writes a pcap.
#include <gtest/gtest.h>

#include <filesystem>

#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/sim/eigen.h"
#include "roadslam/sim/outputs.h"
#include "sim_test_util.h"

using namespace roadslam;
using namespace roadslam::sim;
using sim::test::iniPath;

TEST(SimKittiOutput, FolderRoundTripsThroughLibsDatasets) {
  test::TempDir dir("kitti");
  ScenarioParams p = ScenarioParams::fromFile(iniPath("city-hdl64.ini"));
  p.duration_s = 0.3;
  p.trajectory.start_standing_s = 0;  // moving: the poses differ
  Simulator sim(p);
  OutputOptions opt;
  opt.dir = dir.str();
  const RunReport rep = runToDirectory(sim, opt);
  ASSERT_EQ(rep.stats.sweeps, 3u);
  EXPECT_FALSE(std::filesystem::exists(dir.path / "velodyne.pcap"));
  EXPECT_TRUE(std::filesystem::exists(dir.path / "gt_trajectory.tum"));

  // The same sweeps again in memory (same seed: same points).
  Simulator again(p);
  std::vector<Scan> sweeps;
  again.runSweeps([&](uint64_t, Scan&& s) { sweeps.push_back(std::move(s)); });
  datasets::KittiParams as_written;  // the file's values, without KITTI's elevation correction
  as_written.elevation_correction_rad = 0;
  const datasets::KittiScanFolder folder(dir.str() + "/velodyne", "", as_written);
  ASSERT_EQ(folder.size(), 3u);
  ASSERT_TRUE(folder.hasTimes());
  const datasets::PoseList poses = datasets::readKittiPoses(dir.str() + "/poses_velo_kitti.txt");
  ASSERT_EQ(poses.size(), 3u);
  const Eigen::Isometry3d T0 = toEigen(sim.lidar().lidarPose(sim.lidar().sweepStamp_s(0)));
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(folder.stamp(k), static_cast<double>(p.start_epoch_s) + (k + 0.5) / p.lidar.rotation_hz, 1e-6);
    const Scan s = folder.read(k);
    ASSERT_EQ(s.points.size(), sweeps[k].points.size());
    EXPECT_GT(s.points.size(), 90000u) << "KITTI raw: 98k-123k points per sweep";
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const ScanPoint &a = s.points[i], &b = sweeps[k].points[i];
      ASSERT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z && a.intensity == b.intensity) << k << " " << i;
      ASSERT_GE(a.intensity, 0.0f);
      ASSERT_LE(a.intensity, 1.0f);
    }
    // The first point is fired behind the car, the last just before behind again.
    EXPECT_LT(s.points.front().x, 0.0f);
    EXPECT_LT(s.points.back().x, 0.0f);
    const Eigen::Isometry3d T = T0.inverse() * toEigen(sim.lidar().lidarPose(sim.lidar().sweepStamp_s(k)));
    EXPECT_LT((poses[k].matrix() - T.matrix()).cwiseAbs().maxCoeff(), 1e-8) << k;
  }
  EXPECT_GT(poses[2].translation().x(), 0.01) << "driving forward along the lidar's x";
}

TEST(SimKittiOutput, UdpIsRefusedForTheHdl64) {
  test::TempDir dir("kitti_udp");
  ScenarioParams p = ScenarioParams::fromFile(iniPath("city-hdl64.ini"));
  p.duration_s = 0.1;
  Simulator sim(p);
  OutputOptions opt;
  opt.dir = dir.str();
  opt.udp_host = "127.0.0.1";
  opt.udp_port = 2368;
  EXPECT_THROW(runToDirectory(sim, opt), std::runtime_error);
}
