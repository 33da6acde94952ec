// The NDT grid internals against simple references: std::unordered_map for the flat index, per-voxel
// point lists (two-pass mean/covariance) for the one-pass cell statistics, brute force for the
// nearest-point search.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <map>
#include <random>
#include <unordered_map>

#include "../src/ndt_grid.h"

namespace roadslam::registration {
namespace {

std::vector<Eigen::Vector3d> randomPoints(size_t n, double half_extent_m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-half_extent_m, half_extent_m);
  std::vector<Eigen::Vector3d> pts(n);
  for (auto& p : pts) p = Eigen::Vector3d(u(rng), u(rng), 0.2 * u(rng));
  return pts;
}

TEST(FlatIndex, AgreesWithUnorderedMap) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int64_t> c(-300, 300);
  FlatIndex index(4);  // starts small: the test crosses several rehashes
  std::unordered_map<uint64_t, int32_t> ref;
  for (int i = 0; i < 20000; ++i) {
    const uint64_t k = voxelKey(c(rng), c(rng), c(rng) / 10);
    bool inserted = false;
    const int32_t v = index.findOrInsert(k, inserted);
    const auto [it, fresh] = ref.emplace(k, static_cast<int32_t>(ref.size()));
    ASSERT_EQ(inserted, fresh);
    ASSERT_EQ(v, it->second);
  }
  EXPECT_EQ(index.size(), ref.size());
  for (const auto& [k, v] : ref) ASSERT_EQ(index.find(k), v);
  EXPECT_EQ(index.find(voxelKey(1000, 1000, 1000)), -1);
}

TEST(NdtGrid, ParentKeyIsTheVoxelOfTwiceTheSize) {
  for (const auto& p : randomPoints(5000, 40.0, 3)) {
    for (double res : {0.5, 1.5, 2.0}) ASSERT_EQ(parentKey(voxelKey(p, 1.0 / res)), voxelKey(p, 0.5 / res)) << p.transpose();
  }
}

// Every level's cells equal the statistics of the points in that voxel computed two-pass.
TEST(NdtGrid, CellStatisticsMatchPerVoxelReference) {
  const auto pts = randomPoints(20000, 15.0, 5);
  const double res = 1.0;
  const int levels = 3, min_pts = 5;
  const auto grids = buildNdtGrids(pts, res, levels, min_pts);
  ASSERT_EQ(grids.size(), 3u);
  for (int l = 0; l < levels; ++l) {
    const NdtGrid& g = grids[static_cast<size_t>(l)];
    const double r = res * std::ldexp(1.0, levels - 1 - l);
    EXPECT_DOUBLE_EQ(g.resolution_m, r);
    std::map<uint64_t, std::vector<Eigen::Vector3d>> voxels;
    for (const auto& p : pts) voxels[voxelKey(p, 1.0 / r)].push_back(p);
    ASSERT_EQ(g.index.size(), voxels.size());
    size_t valid = 0;
    for (const auto& [key, v] : voxels) {
      const int32_t c = g.index.find(key);
      ASSERT_GE(c, 0);
      const NdtCell& cell = g.cells[static_cast<size_t>(c)];
      ASSERT_EQ(cell.valid, static_cast<int>(v.size()) >= min_pts);
      if (!cell.valid) continue;
      ++valid;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const auto& p : v) mean += p / static_cast<double>(v.size());
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (const auto& p : v) cov += (p - mean) * (p - mean).transpose() / static_cast<double>(v.size() - 1);
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
      Eigen::Vector3d ev = es.eigenvalues().cwiseMax(0.01 * es.eigenvalues()(2));
      const Eigen::Matrix3d ref_inv = es.eigenvectors() * ev.cwiseInverse().asDiagonal() * es.eigenvectors().transpose();
      EXPECT_LT((cell.mean - mean).norm(), 1e-9);
      EXPECT_LT((cell.cov_inv - ref_inv).norm(), 1e-6 * ref_inv.norm());
      EXPECT_NEAR(std::abs(g.normals[static_cast<size_t>(c)].dot(es.eigenvectors().col(0))), 1.0, 1e-6);
    }
    EXPECT_EQ(g.num_valid, valid);
  }
  EXPECT_EQ(grids.back().bucket_points.size(), pts.size());
}

// Exact wherever the true nearest point is within one cell; nothing beyond max_dist.
TEST(NdtGrid, NearestPointMatchesBruteForceWithinOneCell) {
  const auto pts = randomPoints(4000, 10.0, 9);
  const double res = 1.5, max_d = 1.2;
  const auto grids = buildNdtGrids(pts, res, 1, 5);
  int checked = 0;
  for (const auto& q : randomPoints(2000, 11.0, 10)) {
    double best = 1e30;
    for (const auto& p : pts) best = std::min(best, (p - q).squaredNorm());
    double d2 = 0;
    const int j = nearestInGrid(grids.back(), pts, q, max_d * max_d, d2);
    if (best > max_d * max_d) {
      EXPECT_EQ(j, -1);
      continue;
    }
    ASSERT_GE(j, 0);
    EXPECT_DOUBLE_EQ(d2, best);
    EXPECT_DOUBLE_EQ((pts[static_cast<size_t>(j)] - q).squaredNorm(), best);
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace roadslam::registration
