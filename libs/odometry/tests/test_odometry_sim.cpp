// The odometry on simulated VLP-16 drives, scored against the simulator's exact lidar poses.
#include <gtest/gtest.h>

#include "roadslam/common/config.h"
#include "sim_drive.h"

using namespace roadslam;
using odometry::test::paramsFromIni;
using odometry::test::runSimDrive;

namespace {
std::string src(const std::string& rel) { return std::string(ROADSLAM_SOURCE_DIR) + "/" + rel; }
}  // namespace

// 30 s of the urban loop: 2 s standing, then 270 m along facades, poles and parked cars.
TEST(OdometrySim, DefaultConfigOnTheUrbanLoopStart) {
  const auto r = runSimDrive(src("ini/sim/urban-loop.ini"), 30.0, paramsFromIni(src("ini/default.ini")));
  std::cout << "urban 30 s: ATE " << r.metrics.ate_rmse_m << " m, RTE " << r.metrics.rte_percent << " %\n";
  EXPECT_EQ(r.failed, 0u);
  EXPECT_GT(r.metrics.path_length_m, 250.0);
  EXPECT_LT(r.metrics.rte_percent, 0.25);  // measured 0.091 % (0.16 % before the gravity prior)
  EXPECT_LT(r.metrics.ate_rmse_m, 0.08);   // measured 0.025 m (0.08 m before)
}

// Without the gravity prior the matcher must still take the loop's first corner (at ~30 s): with a
// 3 cm kernel floor (min_threshold_m 0.1) it stuck there and reported standstill (RTE 19 %).
TEST(OdometrySim, WithoutTheGravityPriorTheFirstCornerHolds) {
  auto params = paramsFromIni(src("ini/default.ini"));
  params.gravity_prior = false;
  const auto r = runSimDrive(src("ini/sim/urban-loop.ini"), 40.0, params);
  std::cout << "urban 40 s, no gravity prior: ATE " << r.metrics.ate_rmse_m << " m, RTE " << r.metrics.rte_percent
            << " %\n";
  EXPECT_EQ(r.failed, 0u);
  EXPECT_GT(r.metrics.path_length_m, 350.0);
  EXPECT_LT(r.metrics.rte_percent, 0.5);  // measured 0.17 % (with min_threshold_m 0.1: 18 %)
}

TEST(OdometrySim, HillsKeepTheirHeight) {
  const auto r = runSimDrive(src("ini/sim/hills.ini"), 30.0, paramsFromIni(src("ini/default.ini")));
  std::cout << "hills 30 s: ATE " << r.metrics.ate_rmse_m << " m, RTE " << r.metrics.rte_percent << " %\n";
  EXPECT_EQ(r.failed, 0u);
  EXPECT_LT(r.metrics.rte_percent, 0.25);  // measured 0.069 % (0.36 % before the gravity prior)
}

// The thesis's scan-to-scan pipelines run and are scored; the default pipeline beats both.
TEST(OdometrySim, ThesisConfigsRunAndDefaultBeatsThem) {
  const auto def = runSimDrive(src("ini/sim/urban-loop.ini"), 12.0, paramsFromIni(src("ini/default.ini")));
  for (const char* ini : {"ini/thesis-icp.ini", "ini/thesis-ndt.ini"}) {
    const auto r = runSimDrive(src("ini/sim/urban-loop.ini"), 12.0, paramsFromIni(src(ini)));
    std::cout << ini << ": RTE " << r.metrics.rte_percent << " % (default " << def.metrics.rte_percent << " %)\n";
    EXPECT_GT(r.frames, 100u) << ini;
    EXPECT_LT(r.metrics.rte_percent, 15.0) << ini;  // a working matcher, not a diverged one
    EXPECT_GT(r.metrics.rte_percent, def.metrics.rte_percent) << ini;
  }
}
