// OctoMapBuilder against octomap's own insertPointCloud (the reference implementation) on a
// synthetic scene, and the .bt round trip through octomap's reader.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cstdio>
#include <filesystem>
#include <random>

#include "roadslam/mapping/octo_map.h"
#include "roadslam/mapping/octo_worker.h"

using namespace roadslam::mapping;

namespace {

/// A wall at x = 10 m (y in [-6, 6], z in [-1.5, 2]) and the ground at z = -1.9 m, lidar at the origin.
std::vector<Eigen::Vector3f> scene() {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 20000; ++i) pts.emplace_back(10.0f, -6 + 12 * u(rng), -1.5f + 3.5f * u(rng));
  for (int i = 0; i < 10000; ++i) pts.emplace_back(2 + 7 * u(rng), -5 + 10 * u(rng), -1.9f);
  return pts;
}

bool occupied(const octomap::OcTree& t, double x, double y, double z) {
  const auto* n = t.search(x, y, z);
  return n && t.isNodeOccupied(n);
}
bool freeCell(const octomap::OcTree& t, double x, double y, double z) {
  const auto* n = t.search(x, y, z);
  return n && !t.isNodeOccupied(n);
}

}  // namespace

TEST(OctoMap, AgreesWithOctomapInsertPointCloud) {
  OctoMapParams p;
  p.free_max_range_m = p.max_range_m;  // octomap clears the whole ray
  OctoMapBuilder ours(p), ref(p);
  const auto st = ours.insert(scene(), Eigen::Isometry3d::Identity());
  ref.insertReference(scene(), Eigen::Isometry3d::Identity());
  EXPECT_EQ(st.points, 30000u);
  const auto a = compareOctoMaps(ref.tree(), ours.tree());
  std::printf("agreement: occupied %.1f %% of %zu, free %.1f %% of %zu\n", a.occupied_percent, a.ref_occupied,
              a.free_percent, a.ref_free);
  EXPECT_GT(a.occupied_percent, 99.0);
  EXPECT_GT(a.free_percent, 88.0);  // rays to voxel centres vs to the exact points
  EXPECT_TRUE(occupied(ours.tree(), 10.05, 0.1, 0.1));
  EXPECT_TRUE(freeCell(ours.tree(), 5.0, 0.1, 0.1));
  EXPECT_EQ(ours.tree().search(12.0, 0.1, 0.1), nullptr);  // behind the wall: unknown
}

TEST(OctoMap, FreeSpaceClippedAndPoseApplied) {
  OctoMapParams p;
  p.free_max_range_m = 4.0;
  OctoMapBuilder b(p);
  Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
  T_map_lidar.translation() << 100, 50, 0;
  b.insert(scene(), T_map_lidar);
  EXPECT_TRUE(occupied(b.tree(), 110.05, 50.1, 0.1));
  EXPECT_TRUE(freeCell(b.tree(), 103.0, 50.1, 0.1));
  EXPECT_EQ(b.tree().search(107.0, 50.1, 0.1), nullptr);  // beyond free_max_range_m: not cleared
}

TEST(OctoMap, BtRoundTripKeepsTheBuilderTree) {
  OctoMapBuilder b;
  b.insert(scene(), Eigen::Isometry3d::Identity());
  const size_t leafs = b.numLeafs();
  const std::string path = std::string(ROADSLAM_BINARY_DIR) + "/test-out-octomap.bt";
  b.writeBt(path);
  EXPECT_EQ(b.numLeafs(), leafs);  // writeBinaryConst: the builder's tree is neither pruned nor thresholded
  octomap::OcTree back(0.05);
  ASSERT_TRUE(back.readBinary(path));
  EXPECT_DOUBLE_EQ(back.getResolution(), 0.2);
  EXPECT_TRUE(occupied(back, 10.05, 0.1, 0.1));
  EXPECT_TRUE(freeCell(back, 5.0, 0.1, 0.1));
  std::filesystem::remove(path);
}

TEST(OctoMap, WorkerRebuildEqualsDirectInsertion) {
  OctoMapWorker w(OctoMapParams{});
  Eigen::Isometry3d T1 = Eigen::Isometry3d::Identity(), T2 = T1;
  T2.translation() << 3, 0, 0;
  w.push({scene(), T1});
  w.push({scene(), T1});  // stale poses, replaced by the rebuild
  w.rebuild({{scene(), T1}, {scene(), T2}});
  const auto& map = w.finish();
  EXPECT_EQ(w.inserted(), 2u);
  EXPECT_EQ(w.rebuilds(), 1u);
  OctoMapBuilder direct;
  direct.insert(scene(), T1);
  direct.insert(scene(), T2);
  EXPECT_EQ(map.numLeafs(), direct.numLeafs());
  const auto a = compareOctoMaps(direct.tree(), map.tree());
  EXPECT_DOUBLE_EQ(a.occupied_percent, 100.0);
  EXPECT_DOUBLE_EQ(a.free_percent, 100.0);
}
