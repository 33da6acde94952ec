// The odometry's targets on whole simulated drives (odometry only, ini/default.ini, no CAN):
// relative translation error at most 0.5 % on the highway and the hilly road. Heavy: each drive is
// simulated and matched in full (1,000-1,300 sweeps). The whole urban loop's target is checked on the
// map job's odometry trajectory (MapJobHeavy.FullUrbanLoop), which runs the same odometry over it.
#include <gtest/gtest.h>

#include <iostream>

#include "sim_drive.h"

using namespace roadslam;
using odometry::test::paramsFromIni;
using odometry::test::runSimDrive;

namespace {
std::string src(const std::string& rel) { return std::string(ROADSLAM_SOURCE_DIR) + "/" + rel; }

odometry::test::SimDriveResult drive(const char* scenario) {
  const auto r = runSimDrive(src(std::string("ini/sim/") + scenario + ".ini"), 0.0, paramsFromIni(src("ini/default.ini")));
  std::cout << scenario << ": frames " << r.frames << ", path " << r.metrics.path_length_m << " m, ATE "
            << r.metrics.ate_rmse_m << " m, RTE " << r.metrics.rte_percent << " %, RRE " << r.metrics.rre_deg_per_100m
            << " deg/100 m\n";
  return r;
}
}  // namespace

TEST(OdometrySimFull, HillsWithinTheTarget) {
  const auto r = drive("hills");
  EXPECT_EQ(r.failed, 0u);
  EXPECT_LT(r.metrics.rte_percent, 0.5);  // measured 0.077 %
}

// The hardest start: from standstill on an open road, where single scan rings on the few walls,
// trunks and car sides are most of what observes the forward motion (registration/src/gaussian_voxel_map.cpp).
// Measured 0.163 %; 0.65 % while single rings off the road waited for a second one.
TEST(OdometrySimFull, HighwayWithinTheTarget) {
  const auto r = drive("highway");
  EXPECT_EQ(r.failed, 0u);
  EXPECT_GT(r.metrics.path_length_m, 2900.0);
  EXPECT_LT(r.metrics.rte_percent, 0.5);
}
