#include "roadslam/preprocess/crop_filters.h"

#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <limits>

using namespace roadslam;
using namespace roadslam::preprocess;

namespace {
ScanPoint pt(float x, float y, float z) {
  ScanPoint p;
  p.x = x, p.y = y, p.z = z;
  return p;
}
/// Points on a 0.25 m grid in [-10, 10]^2 at z = -1 (0.25 is exact in binary: no boundary ties).
std::vector<ScanPoint> grid() {
  std::vector<ScanPoint> v;
  for (int i = -40; i <= 40; ++i)
    for (int j = -40; j <= 40; ++j) v.push_back(pt(0.25f * i, 0.25f * j, -1.f));
  return v;
}
}  // namespace

TEST(CropFilters, EgoRadiusRemovesExactlyTheDisc) {
  auto pts = grid();
  const auto in = pts;
  EgoParams p;
  p.radius_m = 2.6;
  size_t expect_removed = 0;
  for (const auto& q : in) expect_removed += std::hypot(q.x, q.y) < 2.6;
  EXPECT_EQ(removeEgo(pts, p), expect_removed);
  EXPECT_EQ(expect_removed, 341u);  // lattice points with i^2 + j^2 < 10.4^2 (counted in Python)
  for (const auto& q : pts) EXPECT_GE(std::hypot(q.x, q.y), 2.6);
  // The z coordinate plays no part: the radius is horizontal.
  std::vector<ScanPoint> tall{pt(1.f, 0.f, 50.f), pt(3.f, 0.f, -50.f)};
  EXPECT_EQ(removeEgo(tall, p), 1u);
  EXPECT_EQ(tall[0].x, 3.f);
}

TEST(CropFilters, RangeKeepsTheShell) {
  std::vector<ScanPoint> pts{pt(0.5f, 0, 0), pt(0, 3, 4), pt(30, 40, 0), pt(60, 80, 0), pt(0, 0, -1.5f)};
  RangeParams p;
  p.min_range_m = 1.0;
  p.max_range_m = 50.0;
  EXPECT_EQ(removeOutOfRange(pts, p), 2u);  // 0.5 m and 100 m; 5 m, 50 m (inclusive) and 1.5 m kept
  ASSERT_EQ(pts.size(), 3u);
  EXPECT_EQ(pts[0].z, 4.f);
  EXPECT_EQ(pts[1].x, 30.f);
  EXPECT_EQ(pts[2].z, -1.5f);
}

TEST(CropFilters, RoiHalfWidthsAndHeights) {
  auto pts = grid();
  RoiParams p;
  p.half_x_m = 5.0;  // |x| <= 5: i in [-20, 20] -> 41 columns
  p.half_y_m = 2.5;  // |y| <= 2.5: j in [-10, 10] -> 21 rows
  EXPECT_EQ(removeOutsideRoi(pts, p), 81u * 81u - 41u * 21u);
  for (const auto& q : pts) EXPECT_TRUE(std::abs(q.x) <= 5 && std::abs(q.y) <= 2.5);
  std::vector<ScanPoint> z{pt(0, 0, -6), pt(0, 0, 4.9f), pt(0, 0, 5.1f)};
  EXPECT_EQ(removeOutsideRoi(z, p), 2u);
}

TEST(CropFilters, NonFiniteDroppedAndCounted) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::vector<ScanPoint> pts{pt(1, 2, 3), pt(nan, 0, 0), pt(0, inf, 0), pt(0, 0, -inf), pt(4, 5, 6)};
  EXPECT_EQ(removeNonFinite(pts), 3u);
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_EQ(pts[1].x, 4.f);
  std::vector<ScanPoint> empty;
  EXPECT_EQ(removeNonFinite(empty), 0u);
  EXPECT_EQ(removeEgo(empty, EgoParams{}), 0u);
}

TEST(CropFilters, ThesisAliasesAndSiKeys) {
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("pre", "rad", std::string("3.5"));
  cfg.write("pre", "xL", std::string("30"));
  cfg.write("pre", "roi_half_y_m", std::string("12"));
  EgoParams e;
  e.loadFromConfigFile(cfg, "pre");
  EXPECT_DOUBLE_EQ(e.radius_m, 3.5);
  RoiParams r;
  r.loadFromConfigFile(cfg, "pre");
  EXPECT_DOUBLE_EQ(r.half_x_m, 30.0);
  EXPECT_DOUBLE_EQ(r.half_y_m, 12.0);
  cfg.write("pre", "ego_radius_m", std::string("2"));
  EXPECT_THROW(e.loadFromConfigFile(cfg, "pre"), std::runtime_error);  // both name and alias
  mrpt::config::CConfigFileMemory bad;
  bad.write("pre", "min_range_m", std::string("abc"));
  try {
    RangeParams rp;
    rp.loadFromConfigFile(bad, "pre");
    FAIL();
  } catch (const std::runtime_error& ex) {
    EXPECT_NE(std::string(ex.what()).find("min_range_m"), std::string::npos) << ex.what();
  }
}
