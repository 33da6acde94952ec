// The whole shipped urban loop (103 s, 990 m, 4 corners of radius 12 m, 35 % parked cars):
// where the boundary stands against the targets (95 % both found, mean <= 0.10 m,
// p95 <= 0.25 m). Not met: parked cars hide the right curb (see the visibility oracle in
// test_sim_drive.cpp) and, in the corners, the eval takes each side as the nearest GT curb on that
// side of the vehicle's x axis (entering a turn the outer curb crosses the axis and becomes the
// "left" GT), so a side that follows its own curb round the corner covers few of those stations.
// This guards what is reached (measured: both 0.684, left 0.753, right 0.843, mean 0.089 m, p95
// 0.172 m; with the path's arc alone, no bend ahead, 0.674 / 0.734 / 0.828 / 0.083 m / 0.223 m; before the arc frame 0.661 / 0.749 / 0.778 / 0.156 m / 0.314 m; before the parallel
// continuation 0.28 / 0.62 / 0.51 / 0.16 m / 0.41 m) and the honesty rules.
#include <gtest/gtest.h>

#include <fstream>

#include "curb_visibility.h"
#include "sim_drive_harness.h"

using namespace roadslam;
using namespace roadslam::jobs::bounds_test;

namespace {

/// Per sweep of a bounds output: the eval's verdict on that sweep alone (both GT sides in the band,
/// both found), the vehicle's heading off the map axes, and the sides' reasons.
struct SweepScore {
  double stamp_s = 0, off_axis_deg = 0;
  int index = 0;
  bool scored = false, found[2] = {false, false};
  std::string reason[2];
};

std::vector<SweepScore> scorePerSweep(const std::string& drive, const std::string& out_dir) {
  const auto curbs = eval::readGtCurbs(drive + "/gt_boundaries.json");
  const auto gt = datasets::readTum(drive + "/gt_trajectory.tum");
  std::ifstream f(out_dir + "/boundaries.jsonl");
  std::vector<SweepScore> out;
  std::string line;
  while (std::getline(f, line)) {
    const auto j = nlohmann::json::parse(line);
    SweepScore s;
    s.stamp_s = j["stamp_s"].get<double>();
    s.index = j["index"].get<int>();
    const double yaw = std::atan2(j["T_map_lidar"][4].get<double>(), j["T_map_lidar"][0].get<double>());
    s.off_axis_deg = std::abs(std::remainder(yaw, M_PI / 2)) * 180 / M_PI;
    const auto m = eval::evaluateBoundaries(curbs, gt, {j});
    s.scored = m.frames_scored == 1;
    s.found[0] = m.left_detected == 1, s.found[1] = m.right_detected == 1;
    for (int k = 0; k < 2; ++k) s.reason[k] = j[k == 0 ? "left" : "right"]["reason"].get<std::string>();
    out.push_back(s);
  }
  return out;
}

/// What is reached on the whole loop (the header's figures) and no vertex on a moving car.
void expectReached(const std::string& drive, const Run& r) {
  EXPECT_GE(r.m.frames_scored, 1000);
  EXPECT_GE(r.m.detection_rate, 0.68);
  EXPECT_GE(r.m.left_detection_rate, 0.75);
  EXPECT_GE(r.m.right_detection_rate, 0.84);
  EXPECT_LE(r.m.lateral_error_mean_m, 0.09);
  // Measured 0.127 m with the ground's parked-car rules (seeds 8 / 9: 0.108 / 0.113 m); without
  // them 0.198 m.
  EXPECT_LE(r.m.lateral_error_p95_m, 0.15);
  // Read along the road ahead (stations on the GT path): corner entries count. Measured 0.714,
  // p95 0.320 m.
  const auto mp = alongPath(drive, r);
  EXPECT_GE(mp.detection_rate, 0.70);
  EXPECT_LE(mp.lateral_error_p95_m, 0.40);
  const auto [on_cars, near] =
      verticesOnMovingCars(drive, r.out_dir);
  EXPECT_GT(near, 20) << "no moving car came near: the check below tests nothing";
  EXPECT_EQ(on_cars, 0) << "boundary vertices on moving cars";
  EXPECT_LT(r.summary["ms_per_frame_mean"].get<double>(), 1e3);  // ran and timed, not a speed check
}

// The ceiling of a detector without prediction on the whole loop: the visibility oracle
// (curb_visibility.h, GT poses and curbs, independent of the detector) marks the sweeps in which
// the sweeps so far put returns on over half of the stations 5-30 m ahead on BOTH sides. Per sweep,
// the eval's verdict (one frame at a time) is split into observable found / observable missed /
// found beyond what was seen (continued parallel, bridged, extrapolated) / never seen.
void expectCeiling(const std::string& drive, const Run& r) {
  const auto views = curbVisibilityBoth(drive, std::string(ROADSLAM_SOURCE_DIR) + "/ini/bounds.ini");
  const auto sweeps = scorePerSweep(drive, r.out_dir);
  int scored = 0, obs = 0, obs_found = 0, obs_missed_corner = 0, unobs = 0, unobs_found = 0;
  int side_obs[2] = {0, 0}, side_obs_found[2] = {0, 0};
  std::ofstream log(std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_loop_ceiling.txt");
  for (const auto& s : sweeps) {
    const auto v = std::find_if(views.begin(), views.end(), [&](const auto& c) { return std::abs(c.stamp_s - s.stamp_s) < 0.01; });
    if (!s.scored || v == views.end() || !v->side[0].gt || !v->side[1].gt) continue;
    ++scored;
    const bool both = s.found[0] && s.found[1];
    for (int k = 0; k < 2; ++k)
      if (v->side[k].accum >= 0.5) ++side_obs[k], side_obs_found[k] += s.found[k];
    if (v->observable()) {
      ++obs, obs_found += both;
      obs_missed_corner += !both && s.off_axis_deg > 1.0;
    } else {
      ++unobs, unobs_found += both;
    }
    log << s.index << " off_axis " << s.off_axis_deg << " obs " << v->observable() << " both " << both;
    for (int k = 0; k < 2; ++k)
      log << (k == 0 ? " | L " : " | R ") << s.found[k] << " seen " << v->side[k].accum << " now " << v->side[k].sweep
          << " '" << s.reason[k] << "'";
    log << "\n";
  }
  const double ceiling = static_cast<double>(obs) / scored;
  std::cout << "whole loop: " << scored << " sweeps scored; both sides observable (oracle) in " << obs << " ("
            << ceiling << " = the ceiling without prediction); found both in " << obs_found << " of them (missed "
            << obs - obs_found << ", " << obs_missed_corner << " of these off the axes > 1 deg); not observable "
            << unobs << ", found both anyway in " << unobs_found << "; left observable " << side_obs[0] << " found "
            << side_obs_found[0] << ", right observable " << side_obs[1] << " found " << side_obs_found[1] << "\n";
  ASSERT_GT(scored, 1000);
  EXPECT_GT(obs, 100) << "the oracle saw too little: the comparison tests nothing";
  EXPECT_LT(ceiling, 0.95) << "the oracle says the target is reachable without prediction: re-read the misses";
  EXPECT_GE(obs_found, 0.70 * obs);  // measured 294 of 402 (path's arc alone 290): the rest are the inner curb at corners (axis stations)
}

}  // namespace

// One bounds job serves both checks: they read the same job on the same inputs (run twice, its two
// outputs differed only in the "ms" fields), and the job is most of their time (as two tests 10.4 s
// and 11.2 s, together 12.3 s).
TEST(SimLoop, WholeUrbanLoopAsReachedAndItsCeiling) {
  const auto drive = cachedDrive("urban-loop.ini", 0.0, nullptr);
  const auto r = runBounds(drive, "bounds.ini", "urban_loop_full");
  {
    SCOPED_TRACE("as reached");
    expectReached(drive, r);
  }
  SCOPED_TRACE("ceiling");
  expectCeiling(drive, r);
}

// The whole shipped hills drive (108 s, 985 m, slopes to ~12 %, parked cars): over long straights
// the sidewalk's far edge, 3.9 m beyond the left curb, gathered more bins than the curb and was
// reported as the left side (p95 4.05 m); the first curb from the vehicle is preferred now
// (inner_curb_share; measured 0.696, mean 0.216 m, p95 0.303 m). Where parked cars hide the right
// curb, lines 5-11 m beyond it (a slope's edge) were taken for it; the road's width rejects them
// now (width_jump_m) and 800 draws make the lines the same for every seed: 0.730, mean 0.091 m,
// p95 0.232 m (seeds 8 / 9: 0.718 / 0.092 / 0.223 and 0.725 / 0.095 / 0.241); with the ground's
// parked-car rules 0.728 / 0.088 / 0.221 (0.728 / 0.097 / 0.218, 0.731 / 0.102 / 0.222): the error targets.
TEST(SimLoop, WholeHillsDriveTakesTheCurbNotTheSidewalksFarEdge) {
  const auto drive = cachedDrive("hills.ini", 0.0, nullptr);
  const auto r = runBounds(drive, "bounds.ini", "hills_full");
  EXPECT_GE(r.m.frames_scored, 1000);
  EXPECT_GE(r.m.detection_rate, 0.72);
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);
}

// Where the curbs can be seen, the targets hold over whole drives: the shipped urban loop and hills
// with their parking lanes empty (every other object as shipped, moving cars included), read along
// the road ahead (path stations: on the axis stations the outer curb crosses the axis mid-corner
// and reads as "left"). Measured: loop 0.965 / 0.044 m / p95 0.149 m, hills 0.982 /
// 0.048 m / 0.185 m; axis stations 0.860 / 0.112 m / 0.063 m and 0.864 / 0.121 m / 0.144 m.
// The shipped drives' misses are the parked cars' (expectCeiling).
TEST(SimLoop, WholeDrivesWithVisibleCurbsMeetTheTargets) {
  for (const auto& [ini, tag] : {std::pair<std::string, std::string>{"urban-loop.ini", "urban_loop_empty_lanes"},
                                 {"hills.ini", "hills_empty_lanes"}}) {
    const auto drive = cachedDrive(ini, 0.0, [](sim::ScenarioParams& p) { p.world.parked_car_prob = 0.0; });
    const auto r = runBounds(drive, "bounds.ini", tag);
    const auto m = alongPath(drive, r);
    EXPECT_GE(m.frames_scored, 1000) << tag;
    EXPECT_GE(m.detection_rate, 0.95) << tag;
    EXPECT_LE(m.lateral_error_mean_m, 0.10) << tag;
    EXPECT_LE(m.lateral_error_p95_m, 0.25) << tag;
    const auto [on_cars, near] = verticesOnMovingCars(drive, r.out_dir);
    EXPECT_GT(near, 20) << tag << ": no moving car came near: the check below tests nothing";
    std::cout << tag << ": boundary vertices within 0.3 m of a moving car " << on_cars << "\n";
    // Hills: 2 vertices (6 without the ground's parked-car rules) in sweeps 971-973, the left line
    // extrapolated 6 m straight past the start of a left corner where an oncoming car turns in (not
    // a car taken for a curb; capping the extrapolation where cells bend away removed 4 of the 6 but
    // cost 0.02 of detection).
    if (tag == "urban_loop_empty_lanes") {
      EXPECT_EQ(on_cars, 0) << tag << ": boundary vertices on moving cars";
    }
    EXPECT_LE(on_cars, 4) << tag;
  }
}

// Whole-drive mode on the shipped drives, parked cars included: each sweep is fitted from the curbs
// of the whole drive along the drive's own path, so what the cars hide from the vehicle ahead was
// seen through the gaps and from behind. The targets hold along the road ahead (path
// stations), with the GT poses and with the odometry's (no loop closure: the loop's start and end
// overlap as the odometry left them). Measured, GT / odometry poses: urban loop 1.000 / 0.004 m /
// 0.023 m and 0.999 / 0.022 m / 0.139 m; hills 1.000 / 0.008 m / 0.022 m and 1.000 / 0.021 m / 0.109 m.
// Two runs of the four: the urban loop (35 % parked cars) with the GT poses, which holds the detector
// to the tight bounds, and the hills drive (the same loop on slopes to 12 %, 30 % parked cars) with
// the odometry's, which adds the odometry's drift, the loop's overlap and the slopes. The urban loop
// with the odometry's poses (21 s) is the hills run's claim on a flat loop, and its first 10 s are
// held to the same bounds by SimDrive.WholeDriveSeesTheCurbParkedCarsHide; the hills drive with GT poses (17 s) is held by the
// odometry's run here and, live, by WholeHillsDriveTakesTheCurbNotTheSidewalksFarEdge.
TEST(SimLoop, WholeDriveModeMeetsTheTargetsBehindParkedCars) {
  struct Case {
    const char* ini;
    const char* tag;
    bool gt;
  };
  for (const Case& c : {Case{"urban-loop.ini", "urban_loop_full", true}, Case{"hills.ini", "hills_full", false}}) {
    const auto drive = cachedDrive(c.ini, 0.0, nullptr);
    const std::string run = std::string(c.tag) + (c.gt ? "_whole_gt" : "_whole_odometry");
    const auto r = runBounds(drive, "bounds.ini", run, {true, c.gt});
    const auto m = alongPath(drive, r);
    EXPECT_GE(m.frames_scored, 1000) << run;
    EXPECT_GE(m.detection_rate, 0.97) << run;
    EXPECT_LE(m.lateral_error_mean_m, c.gt ? 0.02 : 0.05) << run;
    EXPECT_LE(m.lateral_error_p95_m, c.gt ? 0.05 : 0.20) << run;
    const auto [on_cars, near] = verticesOnMovingCars(drive, r.out_dir);
    EXPECT_GT(near, 20) << run << ": no moving car came near: the check below tests nothing";
    EXPECT_EQ(on_cars, 0) << run << ": boundary vertices on moving cars";
  }
}
