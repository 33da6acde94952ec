// Localization on a second drive of the same simulated streets: drive 1 makes the map (a
// keyframe every 2 m at its true poses, written as a map folder and read back), drive 2 starts elsewhere
// on the route (start_offset_m) among other traffic (traffic_seed) and is localized from an unknown
// start. Oracle: the simulator's truth of both drives in one frame (drive 1's world).
#include <gtest/gtest.h>
#include <time.h>

#include <filesystem>
#include <iostream>

#include "../../mapping/tests/sim_drive.h"
#include "roadslam/localization/localizer.h"
#include "roadslam/mapping/map_folder.h"
#include "roadslam/registration/point_cloud.h"

using namespace roadslam;
using namespace roadslam::localization;
using namespace roadslam::mapping;

namespace {

double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

/// The small urban loop of the mapping tests (110 m x 70 m, ~42 s a lap), \p seconds of it.
sim::ScenarioParams smallLoop(double seconds) {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
  p.world.length_m = 110;
  p.world.width_m = 70;
  p.world.moving_cars = 4;
  p.trajectory.start_standing_s = 0.5;
  p.duration_s = seconds;
  return p;
}

/// Map folder of \p frames: a keyframe every 2 m of path at the true poses, points at 0.3 m.
}  // namespace

TEST(SecondDrive, LocalizedInTheFirstDrivesMapFromAnUnknownStart) {
  Eigen::Isometry3d T_sim_w1, T_sim_w2;
  const auto drive1 = test::simulateDrive(smallLoop(30), test::DriftModel{}, &T_sim_w1);
  auto p2 = smallLoop(12);
  p2.world.traffic_seed = 7;             // other traffic
  p2.trajectory.start_offset_m = 60;     // other start, inside the mapped part of the loop
  const auto drive2 = test::simulateDrive(p2, test::DriftModel{}, &T_sim_w2);
  const Eigen::Isometry3d T_w1_w2 = T_sim_w1.inverse() * T_sim_w2;
  ASSERT_GT((T_w1_w2.translation()).norm(), 20.0) << "drive 2 must start elsewhere";

  Localizer loc(gtMapFolder(drive1, drive1.size(), std::string(ROADSLAM_BINARY_DIR) + "/test-out-second-drive-map"));
  int lost = 0, relocalized = 0, n = 0, first_localized = -1;
  double sum_e2 = 0, worst = 0, ms_track = 0, ms_reloc = 0;
  for (size_t i = 0; i < drive2.size(); ++i) {
    const double t0 = threadCpuMs();
    const LocalizationResult l = loc.localize(drive2[i].points_lidar);
    (l.status == LocalizationStatus::Tracked ? ms_track : ms_reloc) += threadCpuMs() - t0;
    if (l.status == LocalizationStatus::Lost) {
      ++lost;
      continue;
    }
    if (first_localized < 0) first_localized = static_cast<int>(i);
    relocalized += l.status == LocalizationStatus::Relocalized ? 1 : 0;
    const double e = (l.T_map_lidar.translation() - (T_w1_w2 * drive2[i].T_world_lidar_gt).translation()).norm();
    sum_e2 += e * e;
    worst = std::max(worst, e);
    ++n;
  }
  const double ate = n > 0 ? std::sqrt(sum_e2 / n) : 1e9;
  const int tracked = n - relocalized;
  std::cout << "second drive: " << drive2.size() << " sweeps, first localized at sweep " << first_localized << ", " << lost
            << " lost, " << relocalized << " relocalizations, ATE " << ate << " m, worst " << worst << " m; thread CPU ms per tracked sweep "
            << ms_track / std::max(1, tracked) << ", per relocalization attempt " << ms_reloc / std::max(1, relocalized + lost)
            << " (map " << loc.mapPoints() << " points)\n";
  ASSERT_GE(first_localized, 0);
  EXPECT_LE(first_localized, 10) << "relocalized within 1 s (10 sweeps)";
  EXPECT_EQ(lost, first_localized) << "never lost once localized";
  EXPECT_LE(relocalized, 1);
  EXPECT_LE(ate, 0.10);
  EXPECT_LE(worst, 0.3);
}
