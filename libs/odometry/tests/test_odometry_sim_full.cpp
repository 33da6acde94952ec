// The odometry issue's targets on whole simulated drives (odometry only, ini/default.ini, no CAN):
// relative translation error at most 0.5 % on the urban loop and the hilly road. Heavy: each drive
// is simulated and matched in full (1,000-1,300 sweeps).
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

TEST(OdometrySimFull, UrbanLoopWithinTheTarget) {
  const auto r = drive("urban-loop");
  EXPECT_EQ(r.failed, 0u);
  EXPECT_GT(r.metrics.path_length_m, 950.0);
  EXPECT_LT(r.metrics.rte_percent, 0.5);  // measured 0.076 %
  EXPECT_LT(r.metrics.ate_rmse_m, 0.5);   // measured 0.12 m
}

TEST(OdometrySimFull, HillsWithinTheTarget) {
  const auto r = drive("hills");
  EXPECT_EQ(r.failed, 0u);
  EXPECT_LT(r.metrics.rte_percent, 0.5);  // measured 0.071 %
}

// Target NOT met on the highway (measured 0.65 %): the pitch error of the first 5 s (accelerating from
// standstill on an open road, few vertical structures) is held by the gravity prior, not undone. This
// bound guards what is reached.
TEST(OdometrySimFull, HighwayBoundedDrift) {
  const auto r = drive("highway");
  EXPECT_EQ(r.failed, 0u);
  EXPECT_LT(r.metrics.rte_percent, 0.9);
}
