// End to end on simulated drives with ground-truth curbs: roadslam-bounds' job (pcap in, given
// poses) scored by libs/eval against the simulator's curb polylines in the 5-30 m band ahead.
// The drives are simulated once into the build folder and reused (cache keyed by the scenario).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

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
  EXPECT_GE(r.m.frames_scored, 110);
  EXPECT_GE(r.m.detection_rate, 0.95);
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);
}

// The shipped urban loop: parked cars (35 % of the slots) hide the right curb for seconds at a
// time (the first 3 s here): the right side is then unknown and says why, never guessed; what is
// reported stays within the accuracy targets, and the left curb is held throughout.
TEST(SimDrive, ParkedCarsHideTheRightCurbAndSaySo) {
  const auto drive = cachedDrive("urban", "urban-loop.ini", 10.0, nullptr);
  const auto r = runBounds(drive, "bounds.ini", "urban");
  EXPECT_GE(r.m.left_detection_rate, 0.95);
  EXPECT_GE(r.m.right_detection_rate, 0.40);  // measured 0.44: hidden for 3 of the 10 s
  EXPECT_LE(r.m.lateral_error_mean_m, 0.10);
  EXPECT_LE(r.m.lateral_error_p95_m, 0.25);
  size_t unexplained = 0;
  std::ifstream f(std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_out_urban/boundaries.jsonl");
  std::string line;
  while (std::getline(f, line)) {
    const auto j = nlohmann::json::parse(line);
    for (const char* s : {"left", "right"})
      if (!j[s]["found"].get<bool>() && j[s]["reason"].get<std::string>().empty()) ++unexplained;
  }
  EXPECT_EQ(unexplained, 0u);
}

TEST(SimDrive, ThesisBaselineRunsOnTheSameDrive) {
  const auto drive = cachedDrive("urban_noparking", "urban-loop.ini", 10.0,
                                 [](sim::ScenarioParams& p) { p.world.parked_car_prob = 0.0; });
  const auto r = runBounds(drive, "bounds-thesis.ini", "urban_thesis");
  EXPECT_GE(r.m.frames_scored, 90);
  EXPECT_EQ(r.summary["method"], "thesis");
}
