// OctoMapBuilder against octomap's own insertPointCloud (the reference implementation) on a
// synthetic scene, and the .bt round trip through octomap's reader.
#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
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

/// Largest |log-odds difference| of \p other at \p reference's leaves; a leaf \p other does not
/// know counts as infinite.
double maxLogOddsDiff(const octomap::OcTree& reference, const octomap::OcTree& other) {
  double d = 0;
  for (auto it = reference.begin_leafs(), end = reference.end_leafs(); it != end; ++it) {
    const octomap::OcTreeNode* n = other.search(it.getKey(), it.getDepth());
    const octomap::OcTreeNode* m = n ? n : other.search(it.getCoordinate());
    if (!m) return std::numeric_limits<double>::infinity();
    d = std::max(d, static_cast<double>(std::fabs(m->getLogOdds() - it->getLogOdds())));
  }
  return d;
}

Eigen::Isometry3d at(double x, double y, double yaw_rad) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() << x, y, 0.3;
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

}  // namespace

// Several keyframes (clamping reached on the wall) and end points beyond max range (free space to
// max range, no hit): the same log-odds as octomap's insertPointCloud at every one of its leaves.
TEST(OctoMap, SameLogOddsAsOctomapOverKeyframes) {
  OctoMapParams p;
  p.max_range_m = 10.5;  // the wall's far corners (up to 11.7 m) lie beyond it
  p.free_max_range_m = p.max_range_m;
  OctoMapBuilder ours(p), ref(p);
  const std::vector<Eigen::Isometry3d> poses = {at(0, 0, 0), at(0.7, 0.2, 0.05), at(1.3, -0.4, -0.1),
                                                at(0, 0, 0), at(0.7, 0.2, 0.05), at(0, 0, 0)};
  for (const auto& T : poses) {
    ours.insert(scene(), T);
    ref.insertReference(scene(), T);
  }
  EXPECT_LT(maxLogOddsDiff(ref.tree(), ours.tree()), 1e-5);
  EXPECT_LT(maxLogOddsDiff(ours.tree(), ref.tree()), 1e-5);
  const auto a = compareOctoMaps(ref.tree(), ours.tree());
  EXPECT_EQ(a.other_unknown, 0u);
  // the comparison covers both clamps (hits of 0.85 up to 3.48, misses of -0.41 down to -1.99)
  size_t at_max = 0, at_min = 0;
  const octomap::OcTree& t = ours.tree();
  for (auto it = t.begin_leafs(), end = t.end_leafs(); it != end; ++it) {
    at_max += it->getLogOdds() == t.getClampingThresMaxLog();
    at_min += it->getLogOdds() == t.getClampingThresMinLog();
  }
  EXPECT_GT(at_max, 100u);
  EXPECT_GT(at_min, 100u);
}

// insertReference() then insert() (the grid re-read from octomap's tree) equals insert() twice.
TEST(OctoMap, MixingReferenceAndOursKeepsOneMap) {
  OctoMapParams p;
  p.free_max_range_m = p.max_range_m;
  OctoMapBuilder mixed(p), ours(p);
  mixed.insertReference(scene(), at(0, 0, 0));
  const size_t voxels_ref = mixed.numVoxels();
  const auto st = mixed.insert(scene(), at(0.7, 0.2, 0.05));
  ours.insert(scene(), at(0, 0, 0));
  EXPECT_EQ(ours.numVoxels(), voxels_ref);
  ours.insert(scene(), at(0.7, 0.2, 0.05));
  EXPECT_GT(st.free_keys, 0u);
  EXPECT_EQ(mixed.numVoxels(), ours.numVoxels());
  EXPECT_LT(maxLogOddsDiff(ours.tree(), mixed.tree()), 1e-5);
  EXPECT_EQ(compareOctoMaps(ours.tree(), mixed.tree()).other_unknown, 0u);
}

TEST(OctoMap, AgreesWithOctomapInsertPointCloud) {
  OctoMapParams p;
  p.free_max_range_m = p.max_range_m;  // octomap clears the whole ray
  OctoMapBuilder ours(p), ref(p);
  const auto st = ours.insert(scene(), Eigen::Isometry3d::Identity());
  ref.insertReference(scene(), Eigen::Isometry3d::Identity());
  EXPECT_EQ(st.points, 30000u);
  EXPECT_EQ(ours.numVoxels(), st.free_keys + st.occupied_keys);
  EXPECT_GE(st.ray_cells, st.free_keys);
  const auto a = compareOctoMaps(ref.tree(), ours.tree());
  std::printf("agreement: occupied %.1f %% of %zu, free %.1f %% of %zu, ours not in octomap %zu\n",
              a.occupied_percent, a.ref_occupied, a.free_percent, a.ref_free, a.other_unknown);
  // same rays (octomap's DDA arithmetic) and the same update: the same map
  EXPECT_DOUBLE_EQ(a.occupied_percent, 100.0);
  EXPECT_DOUBLE_EQ(a.free_percent, 100.0);
  EXPECT_EQ(a.other_unknown, 0u);
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

// .ot keeps the probabilities: octomap's generic reader gives back the builder's log-odds.
TEST(OctoMap, OtRoundTripKeepsLogOdds) {
  OctoMapBuilder b;
  b.insert(scene(), at(0, 0, 0));
  b.insert(scene(), at(0.7, 0.2, 0.05));
  const std::string path = std::string(ROADSLAM_BINARY_DIR) + "/test-out-octomap.ot";
  b.writeOt(path);
  std::unique_ptr<octomap::AbstractOcTree> read(octomap::AbstractOcTree::read(path));
  std::filesystem::remove(path);
  const auto* back = dynamic_cast<const octomap::OcTree*>(read.get());
  ASSERT_NE(back, nullptr) << path;
  EXPECT_EQ(back->getNumLeafNodes(), b.numLeafs());
  EXPECT_EQ(maxLogOddsDiff(b.tree(), *back), 0.0);
  EXPECT_EQ(maxLogOddsDiff(*back, b.tree()), 0.0);
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
