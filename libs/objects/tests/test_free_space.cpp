// FreeSpaceHistory on ray-cast sweeps (synthetic_boxes.h: the oracle is the geometry): a car's points
// after it crossed lie where the rays of a second before reached the road behind (through); a parked
// car's, seen again from a sensor 5 m on, lie where they ended (hit); no sweep near the lag, no
// evidence. And the moving label: a box sliding at 6 m/s whose points were there before stays static.
#include <gtest/gtest.h>

#include <cmath>

#include "roadslam/objects/free_space.h"
#include "roadslam/objects/segmentation.h"
#include "roadslam/objects/tracker.h"
#include "synthetic_boxes.h"

using namespace roadslam;
using namespace roadslam::objects;

namespace {

/// The points of \p scan inside the footprint of \p b (+0.2 m) and above the road, placed by \p T.
std::vector<Eigen::Vector3d> pointsOn(const Scan& scan, const test::SynthBox& b, const Eigen::Isometry3d& T) {
  std::vector<Eigen::Vector3d> out;
  const double c = std::cos(b.yaw), s = std::sin(b.yaw);
  for (const ScanPoint& q : scan.points) {
    const double dx = q.x - b.cx, dy = q.y - b.cy;
    if (std::abs(c * dx + s * dy) <= b.length / 2 + 0.2 && std::abs(-s * dx + c * dy) <= b.width / 2 + 0.2 && q.z > -1.7)
      out.push_back(T * Eigen::Vector3d(q.x, q.y, q.z));
  }
  return out;
}

Eigen::Isometry3d at(double x) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().x() = x;
  return T;
}

}  // namespace

TEST(FreeSpace, ACrossingCarsPlaceWasSeenThroughAParkedCarsWasHit) {
  const test::SynthBox parked{20, 6, 0, 4.5, 1.8, 1.5};
  FreeSpaceHistory h;
  // t = 0: sensor at x = 0, a car crossing at (12, 8) heading -y, the parked car at (20, 6)
  h.add(test::castSweep({{12, 8, -M_PI / 2, 4.5, 1.8, 1.5}, parked}), at(0), 0.0);
  // t = 1: sensor at x = 5 (map), the crossing car at (12, -4) in the map; the parked car where it was
  const test::SynthBox crossed_lidar{7, -4, -M_PI / 2, 4.5, 1.8, 1.5}, parked_lidar{15, 6, 0, 4.5, 1.8, 1.5};
  const Scan now = test::castSweep({crossed_lidar, parked_lidar});
  const auto car_pts = pointsOn(now, crossed_lidar, at(5)), parked_pts = pointsOn(now, parked_lidar, at(5));
  ASSERT_GT(car_pts.size(), 50u);
  ASSERT_GT(parked_pts.size(), 50u);
  const FreeEvidence c = h.check(car_pts, 1.0, 1.0, 0.5), p = h.check(parked_pts, 1.0, 1.0, 0.5);
  EXPECT_GT(c.through, 0.9 * (c.through + c.hit));
  EXPECT_GT(c.through + c.hit, 0.5 * car_pts.size());
  EXPECT_GT(p.hit, 0.8 * (p.through + p.hit));
  EXPECT_GT(p.through + p.hit, 0.5 * parked_pts.size());
  // no sweep within half the lag of t - lag: no evidence
  const FreeEvidence none = h.check(car_pts, 2.0, 0.5, 0.5);
  EXPECT_EQ(none.through + none.hit, 0);
}

TEST(FreeSpace, SweepsWithoutRingsAreImagedByElevation) {
  Scan before = test::castSweep({}, 1800), now = test::castSweep({{10, 0, 0, 4.5, 1.8, 1.5}}, 1800);
  before.has_rings = now.has_rings = false;
  FreeSpaceHistory h;
  h.add(before, at(0), 0.0);
  const FreeEvidence e = h.check(pointsOn(now, {10, 0, 0, 4.5, 1.8, 1.5}, at(0)), 1.0, 1.0, 0.5);
  EXPECT_GT(e.through, 20);
  EXPECT_EQ(e.hit, 0);
}

namespace {

/// A car-sized box sliding along +x at 6 m/s for 3 s, its objects carrying \p through / \p hit evidence.
bool labelledMoving(int through, int hit, const TrackerParams& p = {}) {
  Tracker tr(p);
  for (int k = 0; k <= 30; ++k) {
    Object o;
    o.box = {{10 + 0.6 * k, 5}, 0, 4.5, 1.8, -1.9, -0.4};
    o.centroid = {o.box.centre_m.x(), o.box.centre_m.y(), -1};
    o.points = 100, o.top_height_m = 1.5;
    o.free_through = through, o.free_hit = hit;
    tr.update(0.1 * k, Eigen::Isometry3d::Identity(), {o});
  }
  return tr.tracks().size() == 1 && tr.tracks()[0].moving;
}

}  // namespace

TEST(FreeSpace, ABoxWhosePointsWereThereBeforeIsNeverLabelledMoving) {
  EXPECT_TRUE(labelledMoving(40, 0));
  EXPECT_TRUE(labelledMoving(0, 0));    // no evidence: the label as before
  EXPECT_TRUE(labelledMoving(0, 1));    // too little evidence: 5 points at the 0.8 decay's steady state, < 10
  EXPECT_TRUE(labelledMoving(30, 20));  // most of it free before
  EXPECT_FALSE(labelledMoving(5, 40));  // static clutter sliding as the sensor turns
  TrackerParams off;
  off.moving_min_free_fraction = 0;
  EXPECT_TRUE(labelledMoving(5, 40, off));
}
