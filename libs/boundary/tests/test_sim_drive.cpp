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
#include "roadslam/boundary/job.h"
#include "roadslam/eval/boundary_metrics.h"
#include "roadslam/sim/outputs.h"
#include "roadslam/sim/simulator.h"

namespace fs = std::filesystem;
using namespace roadslam;

namespace {

/// Simulates \p duration_s of \p ini (with \p tweak applied) into the build folder once.
std::string cachedDrive(const std::string& tag, const std::string& ini, double duration_s,
                        void (*tweak)(sim::ScenarioParams&)) {
  const std::string dir = std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_" + tag;
  if (fs::exists(dir + "/summary.json") && fs::exists(dir + "/gt_boundaries.json")) return dir;
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/" + ini);
  p.duration_s = duration_s;
  if (tweak) tweak(p);
  sim::Simulator s(p);
  sim::OutputOptions opt;
  opt.dir = dir;
  sim::runToDirectory(s, opt);
  return dir;
}

struct Run {
  nlohmann::json summary;
  eval::BoundaryMetrics m;
};

Run runBounds(const std::string& drive, const std::string& ini, const std::string& tag) {
  boundary::BoundsRequest req;
  req.config_path = std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + ini;
  req.input_path = drive + "/velodyne.pcap";
  req.trajectory_path = drive + "/gt_trajectory.tum";
  req.out_dir = std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_out_" + tag;
  req.png_every = 25;
  req.progress = false;
  Run r;
  r.summary = boundary::runBoundsJob(req);
  r.m = eval::evaluateBoundaryFiles(drive + "/gt_boundaries.json", drive + "/gt_trajectory.tum",
                                    req.out_dir + "/boundaries.jsonl");
  std::cout << tag << ": " << eval::toJson(r.m).dump() << "\n";
  return r;
}

/// Boundary vertices reported inside a moving car's footprint (+0.3 m), and the frames in which a
/// moving car was within 30 m of the vehicle (so the check had something to reject).
std::pair<int, int> verticesOnMovingCars(const std::string& drive, const std::string& out_dir) {
  std::ifstream fo(drive + "/gt_objects.json");
  const auto objects = nlohmann::json::parse(fo);
  std::ifstream fj(out_dir + "/boundaries.jsonl");
  std::string line;
  int on_cars = 0, near_frames = 0;
  while (std::getline(fj, line)) {
    const auto f = nlohmann::json::parse(line);
    if (!f.contains("left")) continue;
    const double t = f["stamp_s"].get<double>();
    const double vx = f["T_map_lidar"][3].get<double>(), vy = f["T_map_lidar"][7].get<double>();
    bool near = false;
    for (const auto& car : objects["moving_cars"]) {
      const auto& tr = car["track"];
      size_t k = 1;
      while (k + 1 < tr.size() && tr[k][0].get<double>() < t) ++k;
      const double t0 = tr[k - 1][0].get<double>(), t1 = tr[k][0].get<double>();
      const double u = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
      const double cx = (1 - u) * tr[k - 1][1].get<double>() + u * tr[k][1].get<double>();
      const double cy = (1 - u) * tr[k - 1][2].get<double>() + u * tr[k][2].get<double>();
      const double yaw = tr[k][4].get<double>();
      const double hl = 0.5 * car["length_m"].get<double>() + 0.3, hw = 0.5 * car["width_m"].get<double>() + 0.3;
      near = near || std::hypot(cx - vx, cy - vy) < 30.0;
      for (const char* side : {"left", "right"}) {
        if (!f[side]["found"].get<bool>()) continue;
        for (const auto& q : f[side]["polyline_map"]) {
          const double dx = q[0].get<double>() - cx, dy = q[1].get<double>() - cy;
          const double a = std::cos(yaw) * dx + std::sin(yaw) * dy, b = -std::sin(yaw) * dx + std::cos(yaw) * dy;
          on_cars += std::abs(a) <= hl && std::abs(b) <= hw;
        }
      }
    }
    near_frames += near;
  }
  return {on_cars, near_frames};
}

}  // namespace

// Urban loop start (straight street, curbs both sides, trees, poles, oncoming cars), parking lanes
// empty so both curbs are in view: the targets of the issue hold.
TEST(SimDrive, VisibleCurbsMeetTheTargets) {
  const auto drive = cachedDrive("urban_noparking", "urban-loop.ini", 10.0,
                                 [](sim::ScenarioParams& p) { p.world.parked_car_prob = 0.0; });
  const auto r = runBounds(drive, "bounds.ini", "urban_noparking");
  EXPECT_GE(r.m.frames_scored, 90);
  EXPECT_GE(r.m.detection_rate, 0.95);
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);
  EXPECT_TRUE(fs::exists(std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_out_urban_noparking/top_view.png"));
}

// Slopes up to ~12 % with pitch and roll (hills.ini), parking lanes empty: the ground follows the
// hills, the curbs stay found, and boundaries lie on the road so the roll does not shift them.
TEST(SimDrive, HillsMeetTheTargets) {
  const auto drive = cachedDrive("hills_noparking", "hills.ini", 12.0,
                                 [](sim::ScenarioParams& p) { p.world.parked_car_prob = 0.0; });
  const auto r = runBounds(drive, "bounds.ini", "hills_noparking");
  const auto [on_cars, near] = verticesOnMovingCars(drive, std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_out_hills_noparking");
  EXPECT_GT(near, 5) << "no moving car came near: the check below tests nothing";
  EXPECT_EQ(on_cars, 0) << "boundary vertices on moving cars";
  EXPECT_GE(r.m.frames_scored, 110);
  EXPECT_GE(r.m.detection_rate, 0.95);
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);
}

// The shipped urban loop: parked cars (35 % of the slots) hide the right curb. The oracle
// (curb_visibility.h: returns on the GT curb face, detector-independent) says how much of it was in
// view 5-30 m ahead in all sweeps so far: nothing in the first 3.3 s (standing start behind a row of
// cars), and >= half the stations in 43 % of the sweeps. Where the sweeps so far saw >= half of it
// the right side is found from the accumulated curb map; where nothing was ever seen it is unknown
// and says why (or is an explicitly held track), never guessed; the left curb is held throughout.
TEST(SimDrive, ParkedCarsHideTheRightCurbAndSaySo) {
  const auto drive = cachedDrive("urban", "urban-loop.ini", 10.0, nullptr);
  const auto r = runBounds(drive, "bounds.ini", "urban");
  EXPECT_GE(r.m.left_detection_rate, 0.95);
  EXPECT_GE(r.m.right_detection_rate, 0.42);  // measured 0.43 (0.44 with the 10-sweep memory)
  const auto [on_cars, near] = verticesOnMovingCars(drive, std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_out_urban");
  EXPECT_GT(near, 5) << "no moving car came near: the check below tests nothing";
  EXPECT_EQ(on_cars, 0) << "boundary vertices on moving cars";
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);

  const auto view = boundary::test::curbVisibility(drive, std::string(ROADSLAM_SOURCE_DIR) + "/ini/bounds.ini", -1);
  size_t unexplained = 0, seen = 0, seen_found = 0, unseen = 0, unseen_ok = 0;
  std::ifstream f(std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_out_urban/boundaries.jsonl");
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
  const auto drive = cachedDrive("urban_noparking", "urban-loop.ini", 10.0,
                                 [](sim::ScenarioParams& p) { p.world.parked_car_prob = 0.0; });
  const auto r = runBounds(drive, "bounds-thesis.ini", "urban_thesis");
  EXPECT_GE(r.m.frames_scored, 90);
  EXPECT_EQ(r.summary["method"], "thesis");
}
