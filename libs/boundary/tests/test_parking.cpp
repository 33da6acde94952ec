// Perpendicular parking bays: the cars' ends facing the aisle are no curb. Oracle: the
// analytic sweep's own geometry (car boxes and curb lines), independent of the detector.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "roadslam/boundary/curb_map.h"
#include "roadslam/boundary/detector.h"
#include "roadslam/common/config.h"
#include "synthetic_road.h"

using namespace roadslam::boundary;
using roadslam::Scan;
using roadslam::ScanPoint;
using roadslam::boundary::test::Box;
using roadslam::boundary::test::Road;
using roadslam::boundary::test::castSweep;

namespace {

constexpr double kH = 1.9;  // lidar above the road [m]

/// An aisle of ini/sim/parking-lot.ini (synthetic_road.h: 5 m perpendicular bays, 80 % taken, cars
/// 0.3 m off the curbs 9.5 m left and 6.5 m right) with its 0.12 m curbs. Returns the car bodies.
std::vector<Box> parkingLotAisle(Road& road) {
  road.curb_h = 0.12;
  road.sensor_height = kH;
  return roadslam::boundary::test::parkingAisle(road);
}

Params shipped(const std::string& name) {
  Params p;
  p.loadFromConfigFile(*roadslam::loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + name));
  return p;
}

bool onACar(const ScanPoint& q, const std::vector<Box>& bodies, double margin) {
  for (const auto& b : bodies)
    if (q.x > b.x0 - margin && q.x < b.x1 + margin && q.y > b.y0 - margin && q.y < b.y1 + margin) return true;
  return false;
}

struct Counts {
  int on_cars = 0, on_curbs = 0, elsewhere = 0;
};

Counts curbPoints(const Scan& s, const Params& p, const std::vector<Box>& bodies) {
  const Labelling lab = labelPoints(s, p);
  Counts c;
  for (size_t i = 0; i < s.points.size(); ++i) {
    if (lab.cls[i] != PointClass::Curb) continue;
    const auto& q = s.points[i];
    if (std::abs(q.y - 9.5) < 0.15 || std::abs(q.y + 6.5) < 0.15)
      ++c.on_curbs;
    else if (onACar(q, bodies, 0.3))
      ++c.on_cars;
    else
      ++c.elsewhere;
  }
  return c;
}

}  // namespace

TEST(ParkingBays, CarEndsAreNoCurbOverADrive) {
  Road road;
  const auto bodies = parkingLotAisle(road);
  // bounds-parking.ini: ground rules and curb guards; bounds.ini: the ground segmentation's
  // parked-car rules only; before: neither (the defect this test guards).
  const Params p = shipped("bounds-parking.ini"), ground_only = shipped("bounds.ini");
  Params before = ground_only;
  before.ground.parked_car_rules = false;
  ASSERT_DOUBLE_EQ(p.ground.sensor_height_m, kH);
  ASSERT_TRUE(ground_only.ground.parked_car_rules);
  Counts now, mid, old;
  // The vehicle drives along the aisle: the rows shift past it by 0.9 m per sweep.
  for (int k = 0; k < 6; ++k) {
    Road r = road;
    for (auto& b : r.boxes) b.x0 -= 0.9 * k, b.x1 -= 0.9 * k;
    auto shifted = bodies;
    for (auto& b : shifted) b.x0 -= 0.9 * k, b.x1 -= 0.9 * k;
    const Scan s = castSweep(r, 11 + k);
    const Counts c = curbPoints(s, p, shifted), m = curbPoints(s, ground_only, shifted), o = curbPoints(s, before, shifted);
    now.on_cars += c.on_cars, now.on_curbs += c.on_curbs, now.elsewhere += c.elsewhere;
    mid.on_cars += m.on_cars, mid.on_curbs += m.on_curbs, mid.elsewhere += m.elsewhere;
    old.on_cars += o.on_cars, old.on_curbs += o.on_curbs, old.elsewhere += o.elsewhere;
  }
  std::cout << "curb points on cars / on curbs / elsewhere: before " << old.on_cars << " / " << old.on_curbs << " / "
            << old.elsewhere << ", ground rules " << mid.on_cars << " / " << mid.on_curbs << " / " << mid.elsewhere
            << ", ground rules and curb guards " << now.on_cars << " / " << now.on_curbs << " / " << now.elsewhere << "\n";
  EXPECT_GT(old.on_cars, 50);
  EXPECT_EQ(mid.on_cars, 0);  // measured 178 -> 0: the ground no longer starts on the cars' ends
  EXPECT_EQ(now.on_cars, 0);
  EXPECT_EQ(now.elsewhere, 0);
  // The curbs seen through the empty bays stay curbs.
  EXPECT_GT(now.on_curbs, 0);
  EXPECT_GE(now.on_curbs, old.on_curbs * 9 / 10);
  EXPECT_GE(mid.on_curbs, old.on_curbs * 9 / 10);
}

TEST(ParkingBays, CurbCellsWhereASweepSawSomethingStandingAreDropped) {
  // A curb seen from afar along a car's end face (x = 20 m, y = 4.8 m) and the real curb (y = 9.5 m);
  // a later, nearer sweep sees the end face standing 0.6 m above the road.
  CurbMap m(0.2);
  std::vector<Eigen::Vector3d> curb, face;
  for (int k = 0; k < 50; ++k) {
    const double x = 15.1 + 0.2 * k;  // cell centres
    curb.emplace_back(x, 4.81, -1.3), curb.emplace_back(x, 9.51, -1.8);
    face.emplace_back(x, 4.79, -1.3);
  }
  m.insert(curb, 0);
  ASSERT_EQ(m.size(), 100u);
  EXPECT_EQ(m.erase(face, 2), 50u);
  const auto left = m.inVehicle(Eigen::Isometry3d::Identity());
  ASSERT_EQ(left.size(), 50u);
  for (const auto& c : left) EXPECT_NEAR(c.y, 9.51, 1e-9);
  EXPECT_EQ(m.erase({{20.1, 8.9, -1.3}}, 2), 0u);  // its cell 3 cells from the curb's
  EXPECT_EQ(m.erase({{20.1, 9.3, -1.3}}, 2), 5u);  // 1 cell off: the curb cells x = 19.6-20.6 m
}
