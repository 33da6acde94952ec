// CLEAR MOT on hand-made files with known counts: one GT car driving along x at 10 m/s past a
// standing lidar; the tracks follow it 0.1 m off, change id halfway (one switch), and a moving and a
// static track stand where no car is (the moving one is a false positive, the static one is no one's).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

#include <unistd.h>

#include <octomap/OcTree.h>

#include "roadslam/eval/mot_metrics.h"

using namespace roadslam;

namespace {

std::string tmpDir() {
  const std::string d = std::filesystem::temp_directory_path().string() + "/roadslam_mot_test_" + std::to_string(::getpid());
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace

/// The switch tests' drive in \p d: 41 frames at t = 1000 + 0.1 k s (k = 0..40), the lidar standing at
/// the world origin (identity GT and odometry poses: the map frame is the world), one 4.5 x 1.8 x 1.5 m
/// car with the GT samples \p track (gt_objects.json; its speed_mps when \p speed_mps >= 0), and the
/// tracks.csv rows \p rows writes for each frame.
static void writeDrive(const std::string& d, const nlohmann::json& track,
                       const std::function<void(std::ostream&, int, double)>& rows, double speed_mps = -1) {
  nlohmann::json car = {{"id", 0}, {"length_m", 4.5}, {"width_m", 1.8}, {"height_m", 1.5}, {"track", track}};
  if (speed_mps >= 0) car["speed_mps"] = speed_mps;
  const nlohmann::json gt = {{"frame", "world"}, {"moving_cars", {car}}};
  std::ofstream(d + "/gt_objects.json") << gt.dump();
  std::ofstream g(d + "/gt_trajectory.tum"), e(d + "/trajectory_odometry.tum"), tr(d + "/tracks.csv");
  tr << "frame,stamp_s,track_id,x,y,vx,vy,speed_mps,heading_rad,length_m,width_m,z_min,z_max,moving,hits,misses,age_s\n";
  for (int k = 0; k <= 40; ++k) {
    const double t = 1000.0 + 0.1 * k;
    char line[256];
    std::snprintf(line, sizeof(line), "%.6f 0 0 0 0 0 0 1\n", t);
    g << line;
    e << line;
    rows(tr, k, t);
  }
}

TEST(MotMetrics, CountsMatchesSwitchesAndFalsePositivesOfKnownTracks) {
  const std::string d = tmpDir();
  const double t0 = 1000.0;
  nlohmann::json track = nlohmann::json::array();
  for (int k = 0; k <= 40; ++k) track.push_back({t0 + 0.1 * k, -20.0 + 1.0 * k, 5.0, 0.0, 0.0});
  writeDrive(d, track, [](std::ostream& tr, int k, double t) {
    char line[256];
    std::snprintf(line, sizeof(line), "%d,%.6f,%d,%.3f,5.1,10.5,0,10.5,0,4.5,1.8,-1,0.5,1,%d,0,%.2f\n", k, t, k < 20 ? 1 : 2,
                  -20.0 + 1.0 * k, k + 3, k < 20 ? 0.1 * k : 0.1 * (k - 20));
    tr << line;
    std::snprintf(line, sizeof(line), "%d,%.6f,7,10,-10,5,0,5,0,4.5,1.8,-1,0.5,1,20,0,3\n", k, t);
    tr << line;
    std::snprintf(line, sizeof(line), "%d,%.6f,8,-10,-10,0,0,0,0,4.5,1.8,-1,0.5,0,20,0,3\n", k, t);
    tr << line;
  });
  const auto m = eval::evaluateMotFiles(d + "/gt_objects.json", d + "/gt_trajectory.tum", d);
  EXPECT_EQ(m.frames, 41u);
  EXPECT_EQ(m.gt, 41u);  // the car stays within 40 m: x from -20 to 20, y = 5
  EXPECT_EQ(m.matches, 41u);
  EXPECT_EQ(m.misses, 0u);
  EXPECT_EQ(m.id_switches, 1u);
  EXPECT_EQ(m.false_positives, 41u);  // track 7 (moving, no car there); track 8 is static: not counted
  EXPECT_NEAR(m.motp_m, 0.1, 1e-6);
  EXPECT_NEAR(m.mota, 1.0 - (41.0 + 1.0) / 41.0, 1e-9);
  // speed 10.5 against 10 m/s, counted for track ages >= 1 s: track 1 from k = 10..19, track 2 from k = 30..40
  EXPECT_EQ(m.speed_samples, 21u);
  EXPECT_NEAR(m.speed_error_mean_mps, 0.5, 1e-6);
  EXPECT_EQ(m.gt_cars_seen, 1u);
  EXPECT_EQ(m.id_switches_after_gap, 0u);  // the car was matched the frame before (0.1 s)
  EXPECT_EQ(m.id_switches_in_view, 1u);     // ... and never left the view (no returns in the file: by range only)
  eval::MotParams p;
  p.switch_gap_s = 0.05, p.keep_events = true;
  const auto tight = eval::evaluateMotFiles(d + "/gt_objects.json", d + "/gt_trajectory.tum", d, p);
  EXPECT_EQ(tight.id_switches_after_gap, 1u);
  for (const auto& e : tight.events) {
    if (e.kind == "id_switch") {
      EXPECT_NEAR(e.gap_s, 0.1, 1e-6);
    }
  }
  std::filesystem::remove_all(d);
}

TEST(MotMetrics, AMissingTracksFileIsAnErrorNamingIt) {
  const std::string d = tmpDir();
  std::ofstream(d + "/gt_objects.json") << R"({"moving_cars": []})";
  std::ofstream(d + "/gt_trajectory.tum") << "1 0 0 0 0 0 0 1\n";
  std::ofstream(d + "/trajectory_odometry.tum") << "1 0 0 0 0 0 0 1\n";
  try {
    eval::evaluateMotFiles(d + "/gt_objects.json", d + "/gt_trajectory.tum", d);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("tracks.csv"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(d);
}

// Visibility: a car with returns per sample, hidden (3 returns < min_returns 10) in frames 0..9, always
// within 40 m. A moving track follows it except in frames 20..24: its frames on the hidden car are don't
// care (no match, no false positive), the five frames without it are misses; the events list them.
TEST(MotMetrics, HiddenAndFarCarsAreDontCare) {
  const std::string d = tmpDir();
  nlohmann::json track = nlohmann::json::array();
  for (int k = 0; k <= 40; ++k) {
    const double x = -20.0 + 1.1 * k;
    track.push_back({1000.0 + 0.1 * k, x, 5.0, 0.0, 0.0, k < 10 ? 3 : 50, std::hypot(x, 5.0)});
  }
  writeDrive(d, track, [](std::ostream& tr, int k, double t) {
    if (k >= 20 && k < 25) return;  // five frames without a track: five misses
    char line[256];
    std::snprintf(line, sizeof(line), "%d,%.6f,1,%.3f,5.0,11,0,11,0,4.5,1.8,-1,0.5,1,%d,0,%.2f\n", k, t, -20.0 + 1.1 * k,
                  k + 3, 0.1 * k);
    tr << line;
  });
  eval::MotParams p;
  p.keep_events = true;
  const auto m = eval::evaluateMotFiles(d + "/gt_objects.json", d + "/gt_trajectory.tum", d, p);
  EXPECT_EQ(m.gt, 31u);
  EXPECT_EQ(m.dont_care, 10u);
  EXPECT_EQ(m.dont_care_matches, 10u);
  EXPECT_EQ(m.matches, 26u);
  EXPECT_EQ(m.misses, 5u);
  EXPECT_EQ(m.false_positives, 0u);
  EXPECT_EQ(m.id_switches, 0u);
  ASSERT_EQ(m.events.size(), 5u);
  EXPECT_EQ(m.events[0].kind, "miss");
  EXPECT_EQ(m.events[0].returns, 50);
  EXPECT_NE(eval::eventsCsv(m).find("miss"), std::string::npos);
  // the same without visibility (min_returns 0): the hidden frames are matches
  p.min_returns = 0;
  const auto all = eval::evaluateMotFiles(d + "/gt_objects.json", d + "/gt_trajectory.tum", d, p);
  EXPECT_EQ(all.gt, 41u);
  EXPECT_EQ(all.matches, 36u);
  std::filesystem::remove_all(d);
}

// The second id-switch figure: a car followed by track 1 in frames 0..19 and by track 2 from frame 25 on,
// with \p between_returns lidar points on it in frames 20..24 and no track there. With 0 points it left the
// sensor's view: CLEAR MOT's switch stays, KITTI's convention (id_switches_in_view) forgets it; with 5
// (hidden in part, don't care) it stayed in view and both count it.
static eval::MotMetrics switchAcrossFrames(const std::string& d, int between_returns) {
  const double t0 = 1000.0;
  nlohmann::json track = nlohmann::json::array();
  for (int k = 0; k <= 40; ++k) {
    const double x = -20.0 + 1.0 * k;
    track.push_back({t0 + 0.1 * k, x, 5.0, 0.0, 0.0, (k >= 20 && k < 25) ? between_returns : 50, std::hypot(x, 5.0)});
  }
  writeDrive(d, track, [](std::ostream& tr, int k, double t) {
    if (k >= 20 && k < 25) return;
    char line[256];
    std::snprintf(line, sizeof(line), "%d,%.6f,%d,%.3f,5.0,10,0,10,0,4.5,1.8,-1,0.5,1,%d,0,1\n", k, t, k < 20 ? 1 : 2, -20.0 + 1.0 * k,
                  k + 3);
    tr << line;
  });
  eval::MotParams p;
  p.keep_events = true;
  return eval::evaluateMotFiles(d + "/gt_objects.json", d + "/gt_trajectory.tum", d, p);
}

TEST(MotMetrics, ASwitchAfterTheCarLeftTheViewIsCountedApart) {
  const std::string d = tmpDir();
  const auto away = switchAcrossFrames(d, 0);
  EXPECT_EQ(away.id_switches, 1u);
  EXPECT_EQ(away.id_switches_in_view, 0u);
  EXPECT_EQ(away.misses, 0u);  // no point on the car: don't care
  const auto hidden = switchAcrossFrames(d, 5);
  EXPECT_EQ(hidden.id_switches, 1u);
  EXPECT_EQ(hidden.id_switches_in_view, 1u);
  EXPECT_NEAR(hidden.id_switches_in_view_per_100s, hidden.id_switches_per_100s, 1e-9);
  for (const auto* m : {&away, &hidden}) {
    for (const auto& e : m->events) {
      if (e.kind == "id_switch") {
        EXPECT_EQ(e.left_view, m == &away ? 1 : 0);
      }
    }
  }
  EXPECT_NE(eval::eventsCsv(away).find(",0.60,1\n"), std::string::npos) << eval::eventsCsv(away);  // gap_s, left_view
  std::filesystem::remove_all(d);
}

// The simulator's open roads wrap: a car leaving at one end re-enters at the other under its GT id
// (sim World::carPose). Here it jumps 19 m back in one 0.1 s sample at 10 m/s and the tracks, seeing a
// new car, give it a new id: no switch, two cars. Without the file's speed_mps nothing bounds a step,
// and the same files give CLEAR MOT's switch (the test fails if the split is dropped).
TEST(MotMetrics, ACarThatWrapsAroundTheRoadsEndsIsANewCar) {
  const std::string d = tmpDir();
  nlohmann::json track = nlohmann::json::array();
  auto x = [](int k) { return k < 20 ? -20.0 + k : -20.0 + (k - 20); };
  for (int k = 0; k <= 40; ++k) track.push_back({1000.0 + 0.1 * k, x(k), 5.0, 0.0, 0.0, 50, 20.0});
  auto rows = [&](std::ostream& tr, int k, double t) {
    char line[256];
    std::snprintf(line, sizeof(line), "%d,%.6f,%d,%.3f,5.1,10,0,10,0,4.5,1.8,-1,0.5,1,%d,0,%.2f\n", k, t, k < 20 ? 1 : 2, x(k),
                  k + 3, 0.1 * (k % 20));
    tr << line;
  };
  writeDrive(d, track, rows, 10.0);
  eval::MotParams p;
  const auto wrapped = eval::evaluateMotFiles(d + "/gt_objects.json", d + "/gt_trajectory.tum", d, p);
  EXPECT_EQ(wrapped.id_switches, 0u);
  EXPECT_EQ(wrapped.gt_cars_seen, 2u);
  EXPECT_EQ(wrapped.matches, 41u);
  writeDrive(d, track, rows);
  const auto unbounded = eval::evaluateMotFiles(d + "/gt_objects.json", d + "/gt_trajectory.tum", d, p);
  EXPECT_EQ(unbounded.id_switches, 1u);
  EXPECT_EQ(unbounded.gt_cars_seen, 1u);
  std::filesystem::remove_all(d);
}

/// The ghost tests' drive in \p d: one 4.5 x 1.8 x 1.5 m car moving along +x at 10 m/s for 1 s from
/// the world origin (gt_objects.json, 11 samples), the GT lidar standing at the origin
/// (gt_trajectory.tum), and the run's poses \p run_tum (trajectory.tum).
static void writeOneCarDrive(const std::string& d, const std::string& run_tum, int last_seen_sample = 10) {
  nlohmann::json track = nlohmann::json::array();
  for (int k = 0; k <= 10; ++k) track.push_back({1000.0 + 0.1 * k, 1.0 * k, 0.0, 0.0, 0.0, k <= last_seen_sample ? 50 : 0, 5.0});
  const nlohmann::json gt = {{"frame", "world"},
                             {"moving_cars", {{{"id", 0}, {"length_m", 4.5}, {"width_m", 1.8}, {"height_m", 1.5}, {"track", track}}}}};
  std::ofstream(d + "/gt_objects.json") << gt.dump();
  std::ofstream(d + "/gt_trajectory.tum") << "1000 0 0 0 0 0 0 1\n1001 0 0 0 0 0 0 1\n";
  std::ofstream(d + "/trajectory.tum") << run_tum;
}

// Ghost voxels: an OctoMap with one occupied voxel on a car's swept path (0.8 m above its ground,
// inside its box) and one beside the lane; the map frame is the world (identity poses).
TEST(MotMetrics, GhostVoxelsAreTheOccupiedLeavesOnTheSweptPaths) {
  const std::string d = tmpDir();
  writeOneCarDrive(d, "1000 0 0 0 0 0 0 1\n");
  octomap::OcTree tree(0.2);
  tree.updateNode(octomap::point3d(5.0f, 0.3f, 0.8f), true);   // on the path
  tree.updateNode(octomap::point3d(5.0f, 6.0f, 0.8f), true);   // beside it
  tree.updateNode(octomap::point3d(5.0f, -6.0f, 0.8f), false); // free
  ASSERT_TRUE(tree.writeBinary(d + "/map.bt"));
  const auto g = eval::countGhostVoxels(d + "/gt_objects.json", d + "/gt_trajectory.tum", d + "/trajectory.tum", d + "/map.bt");
  EXPECT_EQ(g.map_points, 2u);
  EXPECT_EQ(g.ghost_points, 1u);
  std::filesystem::remove_all(d);
}

// A car the lidar no longer hits (gt_objects.json returns 0 from t = 1000.5: hidden or out of reach)
// puts no point in the map: a point on its later path is a static one (the road there, under a pose's
// attitude error), not a ghost, unless the unseen samples are asked for too.
TEST(MotMetrics, GhostsComeOnlyFromSamplesTheLidarHit) {
  const std::string d = tmpDir();
  writeOneCarDrive(d, "1000 0 0 0 0 0 0 1\n", 5);
  const std::vector<Eigen::Vector3f> pts = {{2.0f, 0.0f, 0.8f},    // the car at t = 1000.2, hit
                                            {9.0f, 0.0f, 0.8f}};   // its path at t = 1000.9, unseen
  EXPECT_EQ(eval::countGhostsAmong(d + "/gt_objects.json", d + "/gt_trajectory.tum", d + "/trajectory.tum", pts).ghost_points, 1u);
  EXPECT_EQ(eval::countGhostsAmong(d + "/gt_objects.json", d + "/gt_trajectory.tum", d + "/trajectory.tum", pts, 0.3, 0, false)
                .ghost_points,
            2u);
  std::filesystem::remove_all(d);
}

// Ghosts under drift: the run's pose slides 3 m sideways over the drive (the GT lidar stands still), so
// the car's points of the last sample entered the map 3 m off its lane. The swept box of each sample is
// carried into the map by the run's pose of its time: the trail there is a ghost, and a point on the
// lane in map coordinates (where no car was placed by the run) is not.
TEST(MotMetrics, GhostsFollowTheRunsPoseOfTheirTimeUnderDrift) {
  const std::string d = tmpDir();
  writeOneCarDrive(d, "1000 0 0 0 0 0 0 1\n1001 0 3 0 0 0 0 1\n");
  const std::vector<Eigen::Vector3f> pts = {{10.0f, 3.0f, 0.8f},   // the car at t = 1001, placed by the drifted pose
                                            {10.0f, 0.0f, 0.8f},   // on the lane in map coordinates: static
                                            {0.0f, 0.0f, 0.8f}};   // the car at t = 1000 (no drift yet)
  const auto g = eval::countGhostsAmong(d + "/gt_objects.json", d + "/gt_trajectory.tum", d + "/trajectory.tum", pts);
  EXPECT_EQ(g.map_points, 3u);
  EXPECT_EQ(g.ghost_points, 2u);
  // only the paths swept within 5 m of the lidar (standing at the origin): the car's first half second
  const auto near = eval::countGhostsAmong(d + "/gt_objects.json", d + "/gt_trajectory.tum", d + "/trajectory.tum", pts, 0.3, 5.0);
  EXPECT_EQ(near.ghost_points, 1u);
  std::filesystem::remove_all(d);
}
