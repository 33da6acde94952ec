// Parked cars' ends are no road. Oracle: a VLP-16-like sweep cast analytically over a
// flat parking aisle (synthetic_road.h: road at -1.9 m, 0.15 m curbs, car bodies 0.25-1.0 m above
// the road as in libs/sim addParkedCar), so every point's surface and true height are known.
#include "roadslam/preprocess/ground_segmentation.h"

#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "synthetic_road.h"

using namespace roadslam;
using namespace roadslam::preprocess;
using namespace roadslam::preprocess::fixtures;

namespace {

constexpr double kH = 1.9;  // lidar above the road [m] (the fixture's default)

/// The fixture's parking aisle shifted by \p dx, its points in \p pts and their truth.
void aisleSweep(double dx, unsigned seed, std::vector<ScanPoint>& pts, std::vector<PointTruth>& truth) {
  Road a;
  parkingAisle(a, dx);
  pts = castSweep(a, seed, &truth).points;
}

/// Points within range by surface; "measured": with a ground line in reach (height not NaN).
struct Tally {
  size_t car = 0, car_ground = 0, car_measured = 0, car_height_ok = 0;
  size_t road = 0, road_measured = 0, road_ground = 0, walk_measured = 0, walk_height_ok = 0;
};

/// Counts within \p max_r of the lidar: car points labelled ground and those whose height above the
/// ground line is within 0.15 m of their true height; road labelled ground; sidewalk heights within
/// 0.06 m of the sidewalk's (the street fixture's sidewalks are ground: curbs are read off the step).
void tally(const std::vector<ScanPoint>& pts, const std::vector<PointTruth>& truth, double max_r, Tally& t,
           bool rules = true, bool level_behind_structure = false) {
  GroundSegParams p;
  p.sensor_height_m = kH;
  p.parked_car_rules = rules;
  p.level_start_behind_structure = level_behind_structure;
  const GroundLabels gl = segmentGroundWithHeights(pts, p);
  for (size_t i = 0; i < pts.size(); ++i) {
    if (std::hypot(pts[i].x, pts[i].y) > max_r) continue;
    const float h = gl.height_above_ground_m[i];
    switch (truth[i].surface) {
      case Surface::Box:
        ++t.car, t.car_ground += gl.ground[i], t.car_measured += !std::isnan(h);
        t.car_height_ok += !std::isnan(h) && std::abs(h - truth[i].height_m) <= 0.15;
        break;
      case Surface::Road:
        ++t.road, t.road_measured += !std::isnan(h), t.road_ground += gl.ground[i];
        break;
      case Surface::Sidewalk:
        t.walk_measured += !std::isnan(h), t.walk_height_ok += !std::isnan(h) && std::abs(h - truth[i].height_m) <= 0.06;
        break;
      case Surface::CurbFace: break;
    }
  }
}

void report(const char* what, const Tally& t) {
  std::cout << what << ": car points " << t.car << ", as ground " << t.car_ground << ", with a height "
            << t.car_measured << ", within 0.15 m of the true one " << t.car_height_ok << "; road " << t.road
            << ", with a height " << t.road_measured << ", as ground " << t.road_ground << "; sidewalk with a height "
            << t.walk_measured << ", within 0.06 m " << t.walk_height_ok << "\n";
}

}  // namespace

// Driving along the aisle (6 sweeps, 0.9 m apart): car ends and bonnets beside the vehicle (inside
// the lowest beam's 7.1 m blind circle) and cars seen over other cars are obstacles standing at their
// true height; the road stays ground and the curbs keep their 0.15 m.
TEST(GroundSegmentationParkedCars, CarEndsInTheAisleAreNoGround) {
  Tally off, t, lv;
  for (int k = 0; k < 6; ++k) {
    std::vector<ScanPoint> pts;
    std::vector<PointTruth> truth;
    aisleSweep(0.9 * k, 11 + k, pts, truth);
    tally(pts, truth, 30.0, off, false);
    tally(pts, truth, 30.0, t);
    tally(pts, truth, 30.0, lv, true, true);
  }
  report("aisle, rules off (default)", off);
  report("aisle, parked_car_rules", t);
  report("aisle, and level start behind structures", lv);
  ASSERT_GT(t.car, 10000u);
  // Without the rules (the default, see the header): 5,293 car points ground, 9,091 of the 22,198
  // with a height within 0.15 m.
  EXPECT_GT(off.car_ground, off.car / 20);
  EXPECT_LT(off.car_height_ok, off.car_measured / 2);
  // With them: left
  // (357, 10,075 of 11,086): bonnets just beyond the blind circle seen over the car's end, which
  // level_start_behind_structure removes (199, 10,195 of 10,592), and end faces 20-30 m away along
  // which a ring grazes (a bridge from the road joins the ring's trace when nothing between them
  // was rejected).
  EXPECT_LE(t.car_ground, t.car / 100);
  // Where a car point gets a height, it is measured from the road, not from a line over the cars.
  EXPECT_GE(t.car_height_ok, t.car_measured * 88 / 100);
  EXPECT_LE(lv.car_ground, lv.car / 200);
  EXPECT_GE(lv.car_height_ok, lv.car_measured * 95 / 100);
  for (const Tally* x : {&t, &lv}) {
    EXPECT_GE(x->road_ground, x->road_measured * 97 / 100);
    EXPECT_GE(x->walk_height_ok, x->walk_measured * 95 / 100);
  }
}

// A car standing in the lane with its end 4 m ahead (inside the blind circle: rings 0-1 hit its end
// face, ring 2 its bonnet), in a street with curbs 4 m left and 3.5 m right.
TEST(GroundSegmentationParkedCars, CarEndAheadInsideTheBlindCircleIsNoGround) {
  Road a;  // curbs 4 m left and 3.5 m right
  a.boxes.push_back({4.0, 8.4, -0.9, 0.9, -kH + 0.25, -kH + 1.0});
  a.boxes.push_back({5.0, 7.4, -0.8, 0.8, -kH + 1.0, -kH + 1.5});
  std::vector<PointTruth> truth;
  const auto pts = castSweep(a, 5, &truth).points;
  Tally off, t;
  tally(pts, truth, 30.0, off, false);
  tally(pts, truth, 30.0, t);
  report("car ahead, rules off", off);
  report("car ahead, parked_car_rules", t);
  ASSERT_GT(t.car, 300u);
  EXPECT_GT(off.car_ground, 100u);                        // 196
  EXPECT_EQ(t.car_ground, 0u);
  EXPECT_GE(t.car_height_ok, t.car_measured * 97 / 100);  // 126 of 126 (rules off: 126 of 486)
  EXPECT_GE(t.road_ground, t.road_measured * 97 / 100);
  EXPECT_GE(t.walk_height_ok, t.walk_measured * 95 / 100);
}

// The switches are ini keys (off by default) and survive a save/load round trip.
TEST(GroundSegmentationParkedCars, SwitchesLoadAndRoundTrip) {
  GroundSegParams def;
  EXPECT_FALSE(def.parked_car_rules);
  EXPECT_FALSE(def.level_start_behind_structure);
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("ground", "seg_parked_car_rules", std::string("true"));
  cfg.write("ground", "seg_level_start_behind_structure", std::string("true"));
  GroundSegParams p;
  p.loadFromConfigFile(cfg, "ground");
  EXPECT_TRUE(p.parked_car_rules);
  EXPECT_TRUE(p.level_start_behind_structure);
  mrpt::config::CConfigFileMemory out;
  p.saveToConfigFile(out, "ground");
  GroundSegParams q;
  q.loadFromConfigFile(out, "ground");
  EXPECT_TRUE(q.parked_car_rules);
  EXPECT_TRUE(q.level_start_behind_structure);
}
