// The whole shipped urban loop (103 s, 990 m, 4 corners of radius 12 m, 35 % parked cars):
// where the boundary stands against the targets (95 % both found, mean <= 0.10 m,
// p95 <= 0.25 m). Not met: parked cars hide the right curb (see the visibility oracle in
// test_sim_drive.cpp) and, in the corners, the eval takes each side as the nearest GT curb on that
// side of the vehicle's x axis (entering a turn the outer curb crosses the axis and becomes the
// "left" GT), so a side that follows its own curb round the corner covers few of those stations.
// This guards what is reached (measured: both 0.674, left 0.734, right 0.828, mean 0.083 m, p95
// 0.223 m; before the arc frame 0.661 / 0.749 / 0.778 / 0.156 m / 0.314 m; before the parallel
// continuation 0.28 / 0.62 / 0.51 / 0.16 m / 0.41 m) and the honesty rules.
#include <gtest/gtest.h>

#include "sim_drive_harness.h"

using namespace roadslam;
using namespace roadslam::boundary::test;

TEST(SimLoop, WholeUrbanLoopAsReached) {
  const auto drive = cachedDrive("urban_loop_full", "urban-loop.ini", 0.0, nullptr);
  const auto r = runBounds(drive, "bounds.ini", "urban_loop_full");
  EXPECT_GE(r.m.frames_scored, 1000);
  EXPECT_GE(r.m.detection_rate, 0.66);
  EXPECT_GE(r.m.left_detection_rate, 0.71);
  EXPECT_GE(r.m.right_detection_rate, 0.80);
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);  // the arc frame: 0.31 m with fits in the vehicle frame
  const auto [on_cars, near] =
      verticesOnMovingCars(drive, std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_out_urban_loop_full");
  EXPECT_GT(near, 20) << "no moving car came near: the check below tests nothing";
  EXPECT_EQ(on_cars, 0) << "boundary vertices on moving cars";
  EXPECT_LT(r.summary["ms_per_frame_mean"].get<double>(), 1e3);  // ran and timed, not a speed check
}
