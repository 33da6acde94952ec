// The objects stage on longer simulated drives (90 s urban loop with 5 moving cars, 60 s parallel
// streets): figures printed against the targets (MOTA >= 0.90, MOTP <= 0.20 m, speed error
// <= 0.5 m/s, <= 1 id switch per 100 tracked s), bounds at the measured figures minus a margin. The GT
// counts the cars the sensor saw (>= 10 returns, eval::MotParams::min_returns) within 40 m. On the
// scenarios' physical traffic (planned corners, car-following) and with the moving label's
// free-space check (ClusterParams::free_space_lag_s); the figures without both in brackets.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "objects_sim_harness.h"

using namespace roadslam;
using namespace roadslam::jobs::objects_test;

TEST(ObjectsSimHeavy, UrbanLoop90s) {
  const ObjectsRun r = runObjects("urban-loop", 90, "urban-loop-90s");
  EXPECT_GE(r.m.gt_cars_seen, 4u);
  // measured 0.981 (0.913: 15 false positives, clutter passed at a corner, 76-78 s, that the free-space
  // check keeps static; 18 on the physical traffic without it; 0.824 before the objects' own ground bridge)
  EXPECT_GE(r.m.mota, 0.93);
  EXPECT_LE(r.m.false_positives, 6u);  // measured 1 (15; 19 on the physical traffic without the free-space check)
  EXPECT_LE(r.m.misses, 25u);   // measured 2 (11, cv 12; 55 before: cars 30-40 m away, their one-ring faces taken for ground)
  EXPECT_LE(r.m.motp_m, 0.16);  // measured 0.108 m (0.109 with the IMM, cv 0.117; 0.124 with a 50 m reach)
  // measured 0.27 m/s (0.125 on constant-speed traffic): the cars brake into the corners and accelerate out
  EXPECT_LE(r.m.speed_error_mean_mps, 0.35);
  // 3 switches (8), all of them cars back in range after 44-51 s around the loop (eval::MotMetrics::id_switches_after_gap)
  EXPECT_LE(r.m.id_switches - r.m.id_switches_after_gap, 2u);  // measured 0 (2, 3 without re-identification, cv 4)
  // the second figure (KITTI's convention): those cars had left the sensor's view (100-330 m away)
  EXPECT_LE(r.m.id_switches_in_view, 2u);  // measured 0 (2: a car turning towards the sensor at 10.5 m/s^2 lateral)
  EXPECT_FALSE(hasNaN(r.out_dir + "/tracks.csv"));
}

TEST(ObjectsSimHeavy, ParallelStreets60s) {
  const ObjectsRun r = runObjects("parallel-streets", 60, "parallel-streets-60s");
  EXPECT_GE(r.m.gt_cars_seen, 2u);
  EXPECT_GE(r.m.mota, 0.93);   // measured 1.000 (1.000; 0.987 when CLEAR MOT counted the wrapped cars' switches; 0.810 before the objects' own ground bridge)
  EXPECT_LE(r.m.misses, 8u);    // measured 0 (27 before)
  EXPECT_LE(r.m.motp_m, 0.16);  // measured 0.130 m (0.130)
  EXPECT_LE(r.m.false_positives, 5u);  // measured 0 (37 before: walls and hedges sliding past, labelled moving)
  // CLEAR MOT's 2 switches were cars that left at a road's end and re-entered 216 m away at the other
  // (the simulator's roads wrap): the evaluation now takes a re-entry for the new car it is
  EXPECT_LE(r.m.id_switches, 1u);  // measured 0 (2 before the split)
  EXPECT_LE(r.m.id_switches_in_view, 1u);  // measured 0
  EXPECT_FALSE(hasNaN(r.out_dir + "/tracks.csv"));
}

// The default [tracking] motion_model = imm on the 30 s loop: the car turning left 30 m away at 3.9 s
// (60 deg/s) keeps its id; with cv its track leaves the constant velocity gate (2 switches, MOTA 0.930,
// MOTP 0.198 m).
TEST(ObjectsSimHeavy, UrbanLoop30sImmKeepsTheTurningCarsId) {
  const ObjectsRun r = runObjects("urban-loop", 30, "urban-loop-30s");
  EXPECT_EQ(r.m.id_switches, 0u);  // measured 0 (1 without re-identification: a car 39 m away, turning behind an occluder, came back as a new track)
  EXPECT_GE(r.m.mota, 0.94);       // measured 0.979 (0.965; 0.953 without re-identification)
  EXPECT_LE(r.m.motp_m, 0.19);     // measured 0.140 m (0.163; 0.166 with the quiet models on moving tracks, 0.161 without re-identification, 0.169 at the 50 m reach)
  EXPECT_LE(r.m.false_positives, 1u);  // measured 0
  // measured 0.41 m/s (0.30; 0.32 with the quiet models on moving tracks; cv: 0.22; the cars in the turn
  // are scored, and now brake into it and accelerate out of it)
  EXPECT_LE(r.m.speed_error_mean_mps, 0.48);
  EXPECT_FALSE(hasNaN(r.out_dir + "/tracks.csv"));
}

static std::string fileText(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Moving-object removal: the same 30 s drive mapped with and without it; ghost points (map points on
// the moving cars' swept paths while the lidar hit them, each placed by the run's pose of its time)
// measured on the physical traffic with the free-space check 1660 -> 43 (97.4 %; within 50 m 1534 -> 30), static points
// lost 0.02 %; on the paths swept within 50 m of the lidar 1370 -> 114, 46 (121, 53): the rest are cars
// too sparse for an object.
// Then the seen-through pass ([seen_through], libs/mapping/seen_through.h) after the tracks' removal:
// what the tracks left (a car's first sweeps before its moving label, cars beyond the objects' reach)
// goes where other sweeps see through it; static points stay; the odometry never sees it.
TEST(ObjectsSimHeavy, RemovalKeepsMostOfTheTrailsOutOfTheMap) {
  const ObjectsRun on = runObjects("urban-loop", 30, "urban-loop-30s", true, true);
  const ObjectsRun off = runObjects("urban-loop", 30, "urban-loop-30s", true, false);
  const std::string& drive = on.drive;
  const auto g_on = eval::countGhostPoints(drive + "/gt_objects.json", drive + "/gt_trajectory.tum",
                                           on.out_dir + "/trajectory.tum", on.out_dir + "/map.ply");
  const auto g_off = eval::countGhostPoints(drive + "/gt_objects.json", drive + "/gt_trajectory.tum",
                                            off.out_dir + "/trajectory.tum", off.out_dir + "/map.ply");
  std::cout << "ghost points with removal " << g_on.ghost_points << " of " << g_on.map_points << ", without "
            << g_off.ghost_points << " of " << g_off.map_points << "\n";
  EXPECT_GT(g_off.ghost_points, 500u);
  EXPECT_LE(g_on.ghost_points, 0.2 * g_off.ghost_points);  // measured 0.026 (0.095 cv, 0.050 IMM; 0.12, 0.074 without the floor)
  const auto n_on = eval::countGhostPoints(drive + "/gt_objects.json", drive + "/gt_trajectory.tum",
                                           on.out_dir + "/trajectory.tum", on.out_dir + "/map.ply", 0.3, 50.0);
  const auto n_off = eval::countGhostPoints(drive + "/gt_objects.json", drive + "/gt_trajectory.tum",
                                            off.out_dir + "/trajectory.tum", off.out_dir + "/map.ply", 0.3, 50.0);
  std::cout << "within 50 m: ghost points with removal " << n_on.ghost_points << ", without " << n_off.ghost_points << "\n";
  EXPECT_LE(n_on.ghost_points, 0.13 * n_off.ghost_points);  // measured 0.083 cv, 0.034 IMM (0.088, 0.039 without the floor)
  const double static_lost = double(g_off.map_points - g_off.ghost_points) - double(g_on.map_points - g_on.ghost_points);
  EXPECT_LE(static_lost, 0.01 * g_off.map_points);  // the bound on static losses
  const ObjectsRun st = runObjects("urban-loop", 30, "urban-loop-30s", true, true, {{"seen_through", "enabled", "true"}}, "-seen-through");
  const auto g_st = eval::countGhostPoints(drive + "/gt_objects.json", drive + "/gt_trajectory.tum",
                                           st.out_dir + "/trajectory.tum", st.out_dir + "/map.ply");
  const auto n_st = eval::countGhostPoints(drive + "/gt_objects.json", drive + "/gt_trajectory.tum",
                                           st.out_dir + "/trajectory.tum", st.out_dir + "/map.ply", 0.3, 50.0);
  std::cout << "seen-through: ghost points " << g_st.ghost_points << ", within 50 m " << n_st.ghost_points << "; pass "
            << st.summary["seen_through"].dump() << "\n";
  ASSERT_GT(st.summary["seen_through"].value("dynamic_voxels", 0), 0);
  EXPECT_LE(g_st.ghost_points, 0.92 * g_on.ghost_points);  // measured 35 of 43 (0.81; 124 of 142 cv, 67 of 74 IMM)
  EXPECT_LE(n_st.ghost_points, 0.92 * n_on.ghost_points);  // measured 23 of 30 (0.77; 96 of 114 cv, 39 of 46 IMM)
  // static points lost to the pass (off the swept paths): measured 64 (0.011 %)
  const double st_lost = double(g_on.map_points - g_on.ghost_points) - double(g_st.map_points - g_st.ghost_points);
  EXPECT_LE(st_lost, 0.001 * g_on.map_points);
  const std::string odo = fileText(st.out_dir + "/trajectory_odometry.tum");
  EXPECT_FALSE(odo.empty());
  EXPECT_EQ(odo, fileText(on.out_dir + "/trajectory_odometry.tum"));
}
