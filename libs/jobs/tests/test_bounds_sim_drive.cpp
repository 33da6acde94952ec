// End to end on simulated drives with ground-truth curbs: roadslam-bounds' job (pcap in, given
// poses) scored by libs/eval against the simulator's curb polylines in the 5-30 m band ahead.
// The drives are simulated once into the build folder and reused (cache keyed by the scenario).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "curb_visibility.h"
#include "sim_drive_harness.h"

namespace fs = std::filesystem;
using namespace roadslam;

using namespace roadslam::jobs::bounds_test;

// Urban loop start (straight street, curbs both sides, trees, poles, oncoming cars), parking lanes
// empty so both curbs are in view: the targets of the issue hold.
TEST(SimDrive, VisibleCurbsMeetTheTargets) {
  const auto drive = cachedDrive("urban-loop.ini", 10.0,
                                 [](sim::ScenarioParams& p) { p.world.parked_car_prob = 0.0; });
  const auto r = runBounds(drive, "bounds.ini", "urban_noparking");
  EXPECT_GE(r.m.frames_scored, 90);
  EXPECT_GE(r.m.detection_rate, 0.95);
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);
  EXPECT_TRUE(fs::exists(r.out_dir + "/top_view.png"));
}

// Slopes up to ~12 % with pitch and roll (hills.ini), parking lanes empty: the ground follows the
// hills, the curbs stay found, and boundaries lie on the road so the roll does not shift them.
TEST(SimDrive, HillsMeetTheTargets) {
  const auto drive = cachedDrive("hills.ini", 12.0,
                                 [](sim::ScenarioParams& p) { p.world.parked_car_prob = 0.0; });
  const auto r = runBounds(drive, "bounds.ini", "hills_noparking");
  const auto [on_cars, near] = verticesOnMovingCars(drive, r.out_dir);
  EXPECT_GT(near, 5) << "no moving car came near: the check below tests nothing";
  EXPECT_EQ(on_cars, 0) << "boundary vertices on moving cars";
  EXPECT_GE(r.m.frames_scored, 110);
  EXPECT_GE(r.m.detection_rate, 0.95);
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);
}

// The same 10 s of the shipped urban loop in whole-drive mode: the first pass drives past the
// parked cars, so the curb they hide from the vehicle ahead was seen through the gaps and from
// behind. The right side is found where the live mode above finds it in 43 % of the sweeps.
TEST(SimDrive, WholeDriveSeesTheCurbParkedCarsHide) {
  const auto drive = cachedDrive("urban-loop.ini", 10.0, nullptr);
  const auto r = runBounds(drive, "bounds.ini", "urban_whole", {true, true});
  EXPECT_EQ(r.summary["mode"], "whole_drive");
  EXPECT_GE(r.m.frames_scored, 90);
  EXPECT_GE(r.m.detection_rate, 0.95);
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);
  const auto [on_cars, near] = verticesOnMovingCars(drive, r.out_dir);
  EXPECT_GT(near, 5) << "no moving car came near: the check below tests nothing";
  EXPECT_EQ(on_cars, 0) << "boundary vertices on moving cars";
  // With the odometry's poses (run once, in the first pass), scored in each estimate's own frame.
  const auto o = runBounds(drive, "bounds.ini", "urban_whole_odometry", {true, false});
  EXPECT_EQ(o.summary["poses"], "odometry");
  EXPECT_EQ(o.summary["frames"], r.summary["frames"]);
  EXPECT_GE(o.m.detection_rate, 0.95);
  EXPECT_LE(o.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(o.m.lateral_error_p95_m, 0.25);
  // ... and along the road ahead, the bounds SimLoop.WholeDriveModeMeetsTheTargetsBehindParkedCars holds
  // the odometry's whole drives to (measured 0.99 / 0.007 m / 0.017 m)
  const auto op = alongPath(drive, o);
  EXPECT_GE(op.detection_rate, 0.97);
  EXPECT_LE(op.lateral_error_mean_m, 0.05);
  EXPECT_LE(op.lateral_error_p95_m, 0.20);
}

// The shipped urban loop: parked cars (35 % of the slots) hide the right curb. The oracle
// (curb_visibility.h: returns on the GT curb face, detector-independent) says how much of it was in
// view 5-30 m ahead in all sweeps so far: nothing in the first 3.3 s (standing start behind a row of
// cars), and >= half the stations in 43 % of the sweeps. Where the sweeps so far saw >= half of it
// the right side is found from the accumulated curb map; where nothing was ever seen it is unknown
// and says why (or is an explicitly held track), never guessed; the left curb is held throughout.
TEST(SimDrive, ParkedCarsHideTheRightCurbAndSaySo) {
  const auto drive = cachedDrive("urban-loop.ini", 10.0, nullptr);
  const auto r = runBounds(drive, "bounds.ini", "urban");
  EXPECT_GE(r.m.left_detection_rate, 0.95);
  EXPECT_GE(r.m.right_detection_rate, 0.42);  // measured 0.43 (0.44 with the 10-sweep memory)
  const auto [on_cars, near] = verticesOnMovingCars(drive, r.out_dir);
  EXPECT_GT(near, 5) << "no moving car came near: the check below tests nothing";
  EXPECT_EQ(on_cars, 0) << "boundary vertices on moving cars";
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);

  const auto view = jobs::bounds_test::curbVisibility(drive, std::string(ROADSLAM_SOURCE_DIR) + "/ini/bounds.ini", -1);
  size_t unexplained = 0, seen = 0, seen_found = 0, unseen = 0, unseen_ok = 0;
  std::ifstream f(r.out_dir + "/boundaries.jsonl");
  std::string line;
  while (std::getline(f, line)) {
    const auto j = nlohmann::json::parse(line);
    for (const char* s : {"left", "right"})
      if (!j[s]["found"].get<bool>() && j[s]["reason"].get<std::string>().empty()) ++unexplained;
    const double t = j["stamp_s"].get<double>();
    const auto v = std::find_if(view.begin(), view.end(), [&](const auto& c) { return std::abs(c.stamp_s - t) < 0.01; });
    if (v == view.end()) continue;
    const bool found = j["right"]["found"].get<bool>();
    if (v->accum >= 0.5) ++seen, seen_found += found;
    if (v->accum == 0) ++unseen, unseen_ok += found && j["right"]["reason"].get<std::string>() == "ok";
  }
  EXPECT_EQ(unexplained, 0u);
  ASSERT_GT(seen, 30u) << "the oracle saw too little of the right curb: the check tests nothing";
  ASSERT_GT(unseen, 30u);
  std::cout << "right curb seen so far (>= half the band) in " << seen << " sweeps, found in " << seen_found
            << "; never seen ahead in " << unseen << ", reported from fresh evidence in " << unseen_ok << "\n";
  EXPECT_GE(seen_found, 0.95 * seen);
  EXPECT_EQ(unseen_ok, 0u);
}

TEST(SimDrive, ThesisBaselineRunsOnTheSameDrive) {
  const auto drive = cachedDrive("urban-loop.ini", 10.0,
                                 [](sim::ScenarioParams& p) { p.world.parked_car_prob = 0.0; });
  const auto r = runBounds(drive, "bounds-thesis.ini", "urban_thesis");
  EXPECT_GE(r.m.frames_scored, 90);
  EXPECT_EQ(r.summary["method"], "thesis");
}
