// The objects stage end to end on a 25 s simulated urban loop (harness: objects_sim_harness.h).
#include <gtest/gtest.h>

#include "objects_sim_harness.h"

using namespace roadslam;
using namespace roadslam::pipeline::objects_test;

TEST(ObjectsSim, UrbanLoop25sTracksTheMovingCars) {
  const ObjectsRun r = runObjects("urban-loop", 25, "urban-loop-25s");
  EXPECT_GE(r.m.gt_cars_seen, 2u);
  EXPECT_GE(r.m.mota, 0.55);  // measured 0.667
  EXPECT_LE(r.m.motp_m, 0.48);  // measured 0.405 m
  EXPECT_LE(r.m.speed_error_mean_mps, 1.0);
  EXPECT_FALSE(hasNaN(r.out_dir + "/tracks.csv"));
  EXPECT_FALSE(hasNaN(r.out_dir + "/objects.csv"));
  // per-frame cost of segmentation + tracking (ground labels apart), wall time on a shared 2-core machine
  EXPECT_LE(r.summary["objects"]["ms_segment_track_per_frame"]["mean"].get<double>(), 15.0);
}
