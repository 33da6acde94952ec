// Segmentation on a ray-cast street of boxes with known poses (oracle: the boxes), and the L-shape
// fit on exact rectangle outlines with a known yaw.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "roadslam/objects/segmentation.h"
#include "synthetic_boxes.h"

using namespace roadslam;
using namespace roadslam::objects;

namespace {

/// Smallest difference of two headings of an undirected axis [rad].
double axisError(double a, double b) {
  const double d = std::fmod(std::abs(a - b), M_PI);
  return std::min(d, M_PI - d);
}

/// For each box, the objects whose centroid falls inside its footprint (+0.3 m).
std::vector<int> objectsPerBox(const std::vector<test::SynthBox>& boxes, const std::vector<Object>& objs) {
  std::vector<int> n(boxes.size(), 0);
  for (const auto& o : objs) {
    for (size_t b = 0; b < boxes.size(); ++b) {
      const double c = std::cos(boxes[b].yaw), s = std::sin(boxes[b].yaw);
      const double dx = o.centroid.x() - boxes[b].cx, dy = o.centroid.y() - boxes[b].cy;
      n[b] += std::abs(c * dx + s * dy) <= boxes[b].length / 2 + 0.3 && std::abs(-s * dx + c * dy) <= boxes[b].width / 2 + 0.3;
    }
  }
  return n;
}

}  // namespace

TEST(Segmentation, EachBoxOfAStreetIsOneObjectWithEveryMethod) {
  const auto boxes = test::streetScene();
  const Scan scan = test::castSweep(boxes);
  for (ClusterMethod m : {ClusterMethod::RangeImage, ClusterMethod::Euclidean, ClusterMethod::Dbscan}) {
    ClusterParams p;
    p.method = m;
    p.min_points = 4;
    SegmentationStats st;
    const auto objs = segmentSweep(scan, p, &st);
    SCOPED_TRACE(toString(m));
    EXPECT_EQ(objs.size(), boxes.size());
    if (objs.size() != boxes.size()) {
      for (const auto& o : objs) {
        std::cout << "object " << o.box.centre_m.x() << "," << o.box.centre_m.y() << " " << o.box.length_m << " x "
                  << o.box.width_m << " yaw " << o.box.yaw_rad << " points " << o.points << " z " << o.box.z_min_m
                  << ".." << o.box.z_max_m << "\n";
      }
    }
    const auto n = objectsPerBox(boxes, objs);
    for (size_t b = 0; b < boxes.size(); ++b) EXPECT_EQ(n[b], 1) << "box " << b;
    EXPECT_GT(st.candidates, 200u);
  }
}

TEST(Segmentation, TwoCarsCloserThanTheDistanceMergeFartherApartSplit) {
  ClusterParams p;
  for (double gap : {0.3, 1.2}) {
    const std::vector<test::SynthBox> boxes = {{10, 4, 0, 4.5, 1.8, 1.5}, {10 + 4.5 + gap, 4, 0, 4.5, 1.8, 1.5}};
    const auto objs = segmentSweep(test::castSweep(boxes), p);
    EXPECT_EQ(objs.size(), gap < p.cluster_distance_m ? 1u : 2u) << "gap " << gap;
  }
}

// DBSCAN's noise: a lone point 0.5 m from a box joins it with the Euclidean method (a chain) but is
// noise for DBSCAN when it has fewer than dbscan_min_points neighbours and no core within eps.
TEST(Segmentation, DbscanLeavesIsolatedPointsOut) {
  const std::vector<test::SynthBox> boxes = {{12, 3, 0, 4.5, 1.8, 1.5}};
  Scan scan = test::castSweep(boxes);
  ClusterParams p;
  p.method = ClusterMethod::Dbscan;
  const auto objs = segmentSweep(scan, p);
  ASSERT_EQ(objs.size(), 1u);
  // a stray point 2 m beyond the box's far end: Euclidean and DBSCAN both leave it out (no object of one);
  // three strays in a row 0.5 m apart: one chain for Euclidean with min_points 3, noise for DBSCAN with MinPts 4
  ScanPoint q = scan.points[objs[0].indices[0]];
  for (int k = 0; k < 3; ++k) {
    ScanPoint r = q;
    r.x = 30.0f + 0.5f * k, r.y = -6.0f, r.z = -0.9f;  // 1 m above the ground
    scan.points.push_back(r);
  }
  // heights from z (no ground labels: the strays alone in their cells would be their own ground)
  const auto g = preprocess::segmentGroundWithHeights(scan.points, p.ground);
  std::vector<uint8_t> ground = g.ground;
  std::vector<float> height = g.height_above_ground_m;
  ground.resize(scan.points.size(), 0);
  height.resize(scan.points.size(), NAN);
  for (size_t i = height.size() - 3; i < height.size(); ++i) ground[i] = 0, height[i] = NAN;
  p.min_points = 3;
  p.method = ClusterMethod::Euclidean;
  EXPECT_EQ(segmentObjects(scan.points, true, ground, height, p).size(), 2u);
  p.method = ClusterMethod::Dbscan;
  p.dbscan_min_points = 4;  // each stray has at most 3 points within 0.6 m (itself included)
  EXPECT_EQ(segmentObjects(scan.points, true, ground, height, p).size(), 1u);
}

TEST(Segmentation, EmptyAndOnePointSweepsGiveNoObjects) {
  ClusterParams p;
  Scan empty;
  empty.has_rings = true;
  EXPECT_TRUE(segmentSweep(empty, p).empty());
  Scan one = empty;
  one.points.push_back({5, 5, 0, 0, 0, 8, 0});
  EXPECT_TRUE(segmentSweep(one, p).empty());
  p.method = ClusterMethod::Dbscan;
  EXPECT_TRUE(segmentSweep(one, p).empty());  // one point is no core: noise
  p.min_points = 1;
  p.method = ClusterMethod::RangeImage;
  const auto objs = segmentSweep(one, p);
  ASSERT_EQ(objs.size(), 1u);
  EXPECT_TRUE(std::isfinite(objs[0].box.centre_m.x()) && std::isfinite(objs[0].box.yaw_rad));
  EXPECT_NEAR(objs[0].box.length_m, 0, 1e-9);
}

// A car rolls out of a turn (Gillespie 1992: 3-7 deg/g; 1.5 deg at 3 m/s^2 with the hard loop's
// 0.5 deg per m/s^2): the road 34 m to its left is 0.89 m lower in the lidar frame. A far car shadows
// its own road, so that no ground line reaches its points (the 90 s hard loop's sweep 783: a car 28 m
// away, every point of it NaN); here their heights are made unknown so. From the rolled ground plane
// they are the true ones (the ray-cast's, before the roll); a level road puts them 0.8 m too low and
// the car below min_top_height_m.
TEST(GroundHeights, PointsNoGroundLineReachesTakeTheirHeightFromTheRolledRoad) {
  std::vector<test::SynthBox> boxes = test::streetScene();
  boxes.push_back({0, 34, 0, 4.5, 1.8, 1.45});
  Scan scan = test::castSweep(boxes);
  std::vector<double> truth;
  const double roll = -1.5 * M_PI / 180, c = std::cos(roll), si = std::sin(roll);
  for (ScanPoint& q : scan.points) {
    truth.push_back(q.z + 1.9);
    const double y = q.y, z = q.z;
    q.y = static_cast<float>(c * y - si * z), q.z = static_cast<float>(si * y + c * z);
  }
  const ClusterParams p;
  preprocess::GroundLabels g = preprocess::segmentGroundWithHeights(scan.points, p.groundParams());
  std::vector<char> on_car(scan.points.size(), 0);
  size_t n_car = 0;
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const ScanPoint& q = scan.points[i];
    on_car[i] = !g.ground[i] && std::abs(q.x) < 2.3 && std::abs(q.y - 34) < 1.25;
    if (on_car[i]) g.height_above_ground_m[i] = NAN, ++n_car;
  }
  ASSERT_GE(n_car, 20u);
  const std::vector<float> unfilled = g.height_above_ground_m;
  EXPECT_GE(fillUnknownHeights(scan.points, g.ground, p.ground.sensor_height_m, g.height_above_ground_m), n_car);
  double worst_filled = 0, worst_level = 0;
  for (size_t i = 0; i < scan.points.size(); ++i) {
    if (!on_car[i]) continue;
    worst_filled = std::max(worst_filled, std::abs(g.height_above_ground_m[i] - truth[i]));
    worst_level = std::max(worst_level, std::abs(scan.points[i].z + p.ground.sensor_height_m - truth[i]));
  }
  EXPECT_LT(worst_filled, 0.05);
  EXPECT_GT(worst_level, 0.8);
  const auto near = [](const std::vector<Object>& objs) {
    return std::count_if(objs.begin(), objs.end(), [](const Object& o) {
      return std::hypot(o.centroid.x(), o.centroid.y() - 34) < 2.0;
    });
  };
  EXPECT_EQ(near(segmentObjects(scan.points, true, g.ground, g.height_above_ground_m, p)), 1);
  EXPECT_EQ(near(segmentObjects(scan.points, true, g.ground, unfilled, p)), 0);
}

// Too few ground points for a plane (a sweep of walls): the level road at -sensor_height_m. The 40
// points span a plane 0.9 m above the level road (z = -1): were they enough, every height would be 0.
TEST(GroundHeights, WithoutGroundPointsTheRoadIsLevel) {
  std::vector<ScanPoint> pts;
  for (int k = 0; k < 40; ++k) pts.push_back({5.0f + 1.5f * (k % 8), -3.0f + 1.5f * (k / 8), -1.0f, 0, 0, 8, 0});
  std::vector<uint8_t> ground(pts.size(), 1);
  std::vector<float> h(pts.size(), NAN);
  EXPECT_EQ(fillUnknownHeights(pts, ground, 1.9, h), pts.size());  // 40 < the 50 a plane needs
  for (float v : h) EXPECT_NEAR(v, 0.9, 1e-6);
  std::vector<float> known(pts.size(), 0.3f);
  EXPECT_EQ(fillUnknownHeights(pts, ground, 1.9, known), 0u);
  EXPECT_FLOAT_EQ(known[0], 0.3f);
}

TEST(LShape, RecoversTheYawOfARectanglesTwoVisibleSides) {
  std::mt19937 rng(21);
  std::normal_distribution<double> noise(0, 0.02);
  for (double yaw_deg : {0.0, 12.0, 33.0, 47.0, 71.0, 89.0, 123.0, 160.0}) {
    const double yaw = yaw_deg * M_PI / 180, L = 4.6, W = 1.8;
    const Eigen::Vector2d c(15, 6), u(std::cos(yaw), std::sin(yaw)), v(-u.y(), u.x());
    // the two sides facing the sensor at the origin: an L of points
    const Eigen::Vector2d su = (c.dot(u) > 0 ? -1.0 : 1.0) * u, sv = (c.dot(v) > 0 ? -1.0 : 1.0) * v;
    std::vector<Eigen::Vector2d> pts;
    for (double a = -L / 2; a <= L / 2; a += 0.05) pts.push_back(c + a * u + W / 2 * sv + noise(rng) * sv);
    for (double b = -W / 2; b <= W / 2; b += 0.05) pts.push_back(c + L / 2 * su + b * v + noise(rng) * su);
    const roadslam::OrientedBox box = fitLShape(pts, M_PI / 180);
    EXPECT_LT(axisError(box.yaw_rad, yaw), 2.0 * M_PI / 180) << "yaw " << yaw_deg << " got " << box.yaw_rad * 180 / M_PI;
    EXPECT_NEAR(box.length_m, L, 0.1);
    EXPECT_NEAR(box.width_m, W, 0.1);
    EXPECT_NEAR(box.centre_m.x(), c.x(), 0.1);
    EXPECT_NEAR(box.centre_m.y(), c.y(), 0.1);
  }
}

TEST(LShape, BoxesOfTheRayCastCarsHaveTheirYaw) {
  const auto boxes = test::streetScene();
  const auto objs = segmentSweep(test::castSweep(boxes), ClusterParams{});
  int checked = 0;
  for (const auto& b : boxes) {
    if (b.length < 2) continue;  // the pole has no axis
    for (const auto& o : objs) {
      const roadslam::OrientedBox& ob = o.box;
      if (std::hypot(ob.centre_m.x() - b.cx, ob.centre_m.y() - b.cy) > 1.5 || ob.length_m < 3.5) continue;  // fully seen cars
      EXPECT_LT(axisError(ob.yaw_rad, b.yaw), 3.0 * M_PI / 180) << "car at " << b.cx << "," << b.cy;
      ++checked;
    }
  }
  EXPECT_GE(checked, 4);
}
