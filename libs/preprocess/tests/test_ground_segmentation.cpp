#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/preprocess/crop_filters.h"
#include "roadslam/preprocess/ground_segmentation.h"
#include "roadslam/preprocess/ransac_ground.h"
#include "synthetic_scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

using namespace roadslam;
using namespace roadslam::preprocess;
using roadslam::preprocess::fixtures::makeStreetSweep;
using roadslam::preprocess::fixtures::StreetScene;

namespace {
struct Score {
  double accuracy, ground_recall, obstacle_recall;
};
Score score(const std::vector<uint8_t>& truth, const std::vector<uint8_t>& got) {
  size_t ok = 0, g = 0, g_ok = 0, o = 0, o_ok = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    ok += truth[i] == got[i];
    if (truth[i]) ++g, g_ok += got[i] == 1;
    else ++o, o_ok += got[i] == 0;
  }
  return {double(ok) / truth.size(), double(g_ok) / std::max<size_t>(g, 1), double(o_ok) / std::max<size_t>(o, 1)};
}
GroundSegParams vlp16Params() {
  GroundSegParams p;
  p.sensor_height_m = 1.8;
  return p;
}
}  // namespace

TEST(GroundSegmentation, StreetWithCrestCurbsWallsAndBox) {
  const auto sweep = makeStreetSweep(StreetScene{});
  ASSERT_GT(sweep.scan.points.size(), 20000u);
  GroundSegStats st;
  const auto labels = segmentGround(sweep.scan.points, vlp16Params(), &st);
  const Score s = score(sweep.ground, labels);
  EXPECT_GE(s.accuracy, 0.95);
  EXPECT_GE(s.ground_recall, 0.93);
  EXPECT_GE(s.obstacle_recall, 0.90);
  EXPECT_EQ(st.ground, static_cast<size_t>(std::count(labels.begin(), labels.end(), 1)));
  EXPECT_GT(st.segments, 0u);
}

// The filter removes exactly the points the labelling calls ground, and keeps the rest in order.
TEST(GroundSegmentation, RemovalKeepsTheUnlabelledPointsInOrder) {
  const auto sweep = makeStreetSweep(StreetScene{});
  const auto labels = segmentGround(sweep.scan.points, vlp16Params());
  std::vector<ScanPoint> kept;
  for (size_t i = 0; i < labels.size(); ++i)
    if (!labels[i]) kept.push_back(sweep.scan.points[i]);
  auto pts = sweep.scan.points;
  EXPECT_EQ(removeGroundLinefit(pts, vlp16Params()), sweep.scan.points.size() - kept.size());
  ASSERT_EQ(pts.size(), kept.size());
  ASSERT_GT(kept.size(), 1000u);
  for (size_t i = 0; i < pts.size(); ++i)
    ASSERT_TRUE(pts[i].x == kept[i].x && pts[i].y == kept[i].y && pts[i].z == kept[i].z) << i;
}

TEST(GroundSegmentation, HoldsOnSlopeWhereASinglePlaneFails) {
  StreetScene scene;
  scene.slope_near = 0.10;  // 5.7 deg climbing ...
  scene.slope_far = -0.05;  // ... then a crest going down
  scene.slope_lateral = 0.03;
  const auto sweep = makeStreetSweep(scene);
  const Score lf = score(sweep.ground, segmentGround(sweep.scan.points, vlp16Params()));
  EXPECT_GE(lf.accuracy, 0.95);
  RansacGroundParams rp;
  rp.max_distance_m = 0.15;
  const auto fit = fitGroundPlaneRansac(sweep.scan.points, rp);
  const Score rs = score(sweep.ground, labelPlaneInliers(sweep.scan.points, fit, rp.max_distance_m));
  EXPECT_GT(lf.accuracy, rs.accuracy);  // the reason for a per-sector method
}

// Heights above the fitted ground against the scene's true terrain: ground points sit on it, and
// the box (a car, 1.5 m) and walls stand out by their true height, which curb detection relies on.
TEST(GroundSegmentation, HeightsAboveGroundMatchTheTerrain) {
  const StreetScene scene;
  const auto sweep = makeStreetSweep(scene);
  const GroundLabels gl = segmentGroundWithHeights(sweep.scan.points, vlp16Params());
  ASSERT_EQ(gl.height_above_ground_m.size(), sweep.scan.points.size());
  EXPECT_EQ(gl.ground, segmentGround(sweep.scan.points, vlp16Params()));
  size_t n = 0, close = 0;
  for (size_t i = 0; i < sweep.scan.points.size(); ++i) {
    const auto& q = sweep.scan.points[i];
    const float h = gl.height_above_ground_m[i];
    if (std::isnan(h) || std::hypot(q.x, q.y) > 30.f) continue;
    ++n;
    close += std::abs(h - (q.z - fixtures::terrainZ(scene, q.x, q.y))) < 0.06;
  }
  EXPECT_GT(n, 15000u);
  EXPECT_GT(double(close) / n, 0.95);
}

TEST(GroundSegmentation, EmptyAndSparseInput) {
  std::vector<ScanPoint> none;
  EXPECT_TRUE(segmentGround(none, vlp16Params()).empty());
  std::vector<ScanPoint> far(3);
  far[0].x = 500.f;  // beyond max range: non-ground, no crash
  far[1].z = -1.8f;  // on the sensor axis
  far[2].x = 5.f, far[2].z = -1.8f;
  far.push_back(far[2]);
  far.back().y = std::numeric_limits<float>::infinity();
  far.push_back(far[2]);
  far.back().z = std::numeric_limits<float>::quiet_NaN();
  const auto l = segmentGround(far, vlp16Params());
  ASSERT_EQ(l.size(), 5u);
  EXPECT_EQ(l[0], 0);
  EXPECT_EQ(l[3], 0);
  EXPECT_EQ(l[4], 0);
}

// KITTI 00 scan 0 (HDL-64E 1.73 m above a street): a plausible share of ground, and the ground
// points lie near z = -1.73 m.
TEST(GroundSegmentation, KittiSweepGroundFractionPlausible) {
  const std::string path = std::string(ROADSLAM_SHARED_DATA) + "/kitti/odometry-00-first16/velodyne/000000.bin";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "missing " << path;
  Scan scan = datasets::readKittiBin(path);
  scan.points.push_back(ScanPoint{});
  scan.points.back().x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(removeNonFinite(scan.points), 1u);
  GroundSegParams p;  // KITTI defaults: sensor_height_m = 1.73
  const auto labels = segmentGround(scan.points, p);
  double zsum = 0;
  size_t g = 0, near_ground = 0;
  for (size_t i = 0; i < labels.size(); ++i) {
    if (!labels[i]) continue;
    ++g, zsum += scan.points[i].z;
    const float r = std::hypot(scan.points[i].x, scan.points[i].y);
    near_ground += r < 20 && std::abs(scan.points[i].z + 1.73f) < 0.3f;
  }
  const double frac = double(g) / labels.size();
  EXPECT_GT(frac, 0.3);
  EXPECT_LT(frac, 0.7);
  EXPECT_NEAR(zsum / g, -1.7, 0.3);
  EXPECT_GT(near_ground, g / 3);
}
