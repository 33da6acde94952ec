// The objects stage end to end on a 25 s simulated urban loop (harness: objects_sim_harness.h).
#include <gtest/gtest.h>

#include "objects_sim_harness.h"

using namespace roadslam;
using namespace roadslam::pipeline::objects_test;

TEST(ObjectsSim, UrbanLoop25sTracksTheMovingCars) {
  const ObjectsRun r = runObjects("urban-loop", 25, "urban-loop-25s");
  EXPECT_GE(r.m.gt_cars_seen, 2u);
  EXPECT_GE(r.m.mota, 0.74);  // measured 0.826 (GT: cars seen with >= 10 returns)
  EXPECT_LE(r.m.motp_m, 0.28);  // measured 0.227 m
  EXPECT_LE(r.m.speed_error_mean_mps, 0.5);  // measured 0.25 m/s
  EXPECT_FALSE(hasNaN(r.out_dir + "/tracks.csv"));
  EXPECT_FALSE(hasNaN(r.out_dir + "/objects.csv"));
  // per-frame cost of segmentation + tracking (ground labels apart), wall time on a shared 2-core machine
  EXPECT_LE(r.summary["objects"]["ms_segment_track_per_frame"]["mean"].get<double>(), 15.0);
}

// The options on the same drive: DBSCAN clustering and the CTRV motion model (measured MOTA 0.802,
// MOTP 0.230 m; range image + CV: 0.826, 0.227 m).
TEST(ObjectsSim, DbscanAndCtrvTrackTheMovingCarsToo) {
  const ObjectsRun r = runObjects("urban-loop", 25, "urban-loop-25s", false, true,
                                  {{"method = range_image", "method = dbscan"}, {"motion_model = cv", "motion_model = ctrv"}},
                                  "-dbscan-ctrv");
  EXPECT_EQ(r.summary["objects"]["tracks_ended"].value("diverged", 0), 0);
  EXPECT_GE(r.m.mota, 0.72);
  EXPECT_LE(r.m.motp_m, 0.28);
  EXPECT_FALSE(hasNaN(r.out_dir + "/tracks.csv"));
}
