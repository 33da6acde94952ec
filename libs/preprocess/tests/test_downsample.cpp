#include "roadslam/preprocess/downsample.h"

#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <random>
#include <set>
#include <tuple>

using namespace roadslam;
using namespace roadslam::preprocess;

namespace {
std::vector<ScanPoint> randomCloud(size_t n, unsigned seed, float half = 20.f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-half, half);
  std::vector<ScanPoint> v(n);
  for (size_t i = 0; i < n; ++i) {
    v[i].x = u(rng), v[i].y = u(rng), v[i].z = u(rng) * 0.1f;
    v[i].intensity = static_cast<float>(i % 256);
    v[i].ring = static_cast<uint16_t>(i);  // identifies the source point
  }
  return v;
}
using Key = std::tuple<int32_t, int32_t, int32_t>;
}  // namespace

TEST(RandomDownsample, ExactCountOrderedSubsetDeterministic) {
  const auto in = randomCloud(10001, 1);
  RandomDownsampleParams p;
  p.keep_fraction = 0.3;
  auto a = in, b = in;
  EXPECT_EQ(randomDownsample(a, p), 10001u - 3000u);
  ASSERT_EQ(a.size(), 3000u);  // round(0.3 * 10001)
  randomDownsample(b, p);
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].ring, b[i].ring);
  for (size_t i = 1; i < a.size(); ++i) EXPECT_LT(a[i - 1].ring, a[i].ring);  // order kept, no repeats
  // Uniform: each half of the input contributes about half of the output.
  const auto first_half = std::count_if(a.begin(), a.end(), [](const ScanPoint& q) { return q.ring < 5000; });
  EXPECT_NEAR(static_cast<double>(first_half), 1500.0, 120.0);
  p.seed = 2;
  auto c = in;
  randomDownsample(c, p);
  size_t same = 0;
  for (size_t i = 0; i < c.size(); ++i) same += c[i].ring == a[i].ring;
  EXPECT_LT(same, c.size());
  p.keep_fraction = 1.0;
  auto d = in;
  EXPECT_EQ(randomDownsample(d, p), 0u);
}

TEST(VoxelGrid, CountsAndCentroidsMatchBruteForce) {
  const auto in = randomCloud(20000, 4);
  for (double size : {0.2, 0.5, 1.3}) {
    std::map<Key, std::vector<size_t>> ref;  // independent reference: ordered map of member indices
    for (size_t i = 0; i < in.size(); ++i) {
      const VoxelKey k = voxelOf(in[i], size);
      ref[{k.ix, k.iy, k.iz}].push_back(i);
    }
    auto pts = in;
    VoxelParams p;
    p.voxel_size_m = size;
    EXPECT_EQ(voxelDownsample(pts, p), in.size() - ref.size()) << size;
    ASSERT_EQ(pts.size(), ref.size());
    for (const auto& q : pts) {
      const auto& members = ref.at({voxelOf(in[q.ring], size).ix, voxelOf(in[q.ring], size).iy,
                                    voxelOf(in[q.ring], size).iz});
      EXPECT_EQ(members.front(), q.ring);  // the first point's attributes are carried
      double cx = 0, cz = 0;
      for (size_t m : members) cx += in[m].x, cz += in[m].z;
      EXPECT_NEAR(q.x, cx / members.size(), 1e-4);
      EXPECT_NEAR(q.z, cz / members.size(), 1e-4);
    }
    auto first = in;
    p.mode = VoxelParams::Mode::First;
    voxelDownsample(first, p);
    ASSERT_EQ(first.size(), ref.size());
    std::set<size_t> firsts;
    for (const auto& kv : ref) firsts.insert(kv.second.front());
    for (const auto& q : first) {
      EXPECT_TRUE(firsts.count(q.ring));
      EXPECT_EQ(q.x, in[q.ring].x);
    }
  }
}

TEST(VoxelGrid, NegativeCoordinatesAndEmpty) {
  std::vector<ScanPoint> pts(4);
  pts[0].x = -0.01f, pts[1].x = 0.01f, pts[2].x = -0.49f, pts[3].x = -0.51f;
  VoxelParams p;
  p.voxel_size_m = 0.5;  // voxels [-1,-0.5), [-0.5,0), [0,0.5): floor, not truncation
  EXPECT_EQ(voxelDownsample(pts, p), 1u);
  EXPECT_EQ(pts.size(), 3u);
  std::vector<ScanPoint> none;
  EXPECT_EQ(voxelDownsample(none, p), 0u);
  std::vector<ScanPoint> bad(3);
  bad[0].x = std::numeric_limits<float>::quiet_NaN();
  bad[1].y = 1e12f;  // finite but beyond the key range
  EXPECT_EQ(voxelDownsample(bad, p), 2u);
  ASSERT_EQ(bad.size(), 1u);
  EXPECT_EQ(bad[0].y, 0.f);
}

TEST(StatisticalOutlierRemoval, RemovesInjectedOutliers) {
  std::vector<ScanPoint> pts;
  for (int i = 0; i < 60; ++i)
    for (int j = 0; j < 60; ++j) {
      ScanPoint q;
      q.x = 0.1f * i, q.y = 0.1f * j, q.z = 0.f;
      pts.push_back(q);
    }
  const size_t inliers = pts.size();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-30.f, 30.f);
  for (int k = 0; k < 30; ++k) {
    ScanPoint q;
    q.x = u(rng), q.y = u(rng), q.z = 5.f + std::abs(u(rng));  // far from the sheet and each other
    q.ring = 1;  // marks an outlier
    pts.push_back(q);
  }
  SorParams p;
  p.k = 8;
  p.std_mul = 1.0;
  const size_t removed = removeStatisticalOutliers(pts, p);
  for (const auto& q : pts) EXPECT_EQ(q.ring, 0) << q.x << " " << q.y << " " << q.z;
  EXPECT_GE(removed, 30u);
  EXPECT_LE(removed, 30u + inliers / 100);
  std::vector<ScanPoint> few(5);
  EXPECT_EQ(removeStatisticalOutliers(few, p), 0u);
}
