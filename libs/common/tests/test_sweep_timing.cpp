// Times from the azimuth against hand-worked firing order: a clockwise sensor cut behind the car
// fires left (a quarter turn), forward (half), right (three quarters); a counter-clockwise one the
// mirror image; the stamp moves to the first firing by the reference's share of the period.
#include <gtest/gtest.h>

#include <cmath>

#include "roadslam/common/sweep_timing.h"

using namespace roadslam;

namespace {
Scan fourPoints(double stamp_s) {
  Scan s;
  s.stamp_s = stamp_s;
  for (const auto& [x, y] : {std::pair{1.f, 0.f}, {0.f, 1.f}, {-1.f, 0.001f}, {0.f, -1.f}}) {
    ScanPoint p;
    p.x = x;
    p.y = y;
    s.points.push_back(p);
  }
  return s;  // forward, left, just left of behind, right
}
}  // namespace

TEST(SweepTiming, ClockwiseCutBehindFiresLeftForwardRight) {
  Scan s = fourPoints(10.0);
  timesFromAzimuth(s, SweepTiming{0.1, SpinDirection::Clockwise, 180.0, StampReference::Middle});
  EXPECT_NEAR(s.points[0].t, 0.05, 1e-6);   // forward: the middle
  EXPECT_NEAR(s.points[1].t, 0.025, 1e-6);  // left: a quarter
  EXPECT_NEAR(s.points[2].t, 0.0, 1e-4);    // just past the cut
  EXPECT_NEAR(s.points[3].t, 0.075, 1e-6);  // right
  EXPECT_DOUBLE_EQ(s.stamp_s, 10.0 - 0.05);
  EXPECT_TRUE(s.has_point_times);
  EXPECT_STREQ(pointTimesName(s), "azimuth");
}

TEST(SweepTiming, CounterClockwiseAndOtherCutsAndReferences) {
  Scan s = fourPoints(1.0);
  timesFromAzimuth(s, SweepTiming{0.2, SpinDirection::CounterClockwise, 0.0, StampReference::End});
  EXPECT_NEAR(s.points[0].t, 0.0, 1e-6);   // the cut itself
  EXPECT_NEAR(s.points[1].t, 0.05, 1e-6);  // left after a quarter of 0.2 s
  EXPECT_NEAR(s.points[2].t, 0.1, 1e-4);   // behind after half
  EXPECT_NEAR(s.points[3].t, 0.15, 1e-6);
  EXPECT_DOUBLE_EQ(s.stamp_s, 1.0 - 0.2);
  Scan t = fourPoints(1.0);
  timesFromAzimuth(t, SweepTiming{0.1, SpinDirection::Clockwise, 90.0, StampReference::Start});
  EXPECT_NEAR(t.points[1].t, 0.0, 1e-6);    // left is the cut
  EXPECT_NEAR(t.points[0].t, 0.025, 1e-6);  // then forward
  EXPECT_DOUBLE_EQ(t.stamp_s, 1.0);
}

TEST(SweepTiming, NamesParseAndBadOnesAreNamed) {
  EXPECT_EQ(spinDirectionFromString("counterclockwise", "k"), SpinDirection::CounterClockwise);
  EXPECT_EQ(stampReferenceFromString(toString(StampReference::Middle), "k"), StampReference::Middle);
  try {
    stampReferenceFromString("centre", "[kitti] stamp_reference");
    FAIL() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("[kitti] stamp_reference = 'centre'"), std::string::npos) << e.what();
  }
  Scan none;
  EXPECT_STREQ(pointTimesName(none), "none");
  none.has_point_times = true;
  EXPECT_STREQ(pointTimesName(none), "sensor");
}
