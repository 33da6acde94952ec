// A folder from the real map job (a simulated 4 s of the urban loop, [objects] enabled) read back
// through the run-folder readers, against what the job returned in memory and the simulator's truth.
// One TEST: ctest runs each TEST as a process of its own, and two of them at once would run the same
// job into one folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "roadslam/jobs/map_job.h"
#include "roadslam/runfolder/run_folder.h"
#include "roadslam/sim/outputs.h"
#include "test_util.h"

using namespace roadslam;

namespace {

struct JobRun {
  std::string drive, dir;
  jobs::MapOutcome out;
};

JobRun runJob() {
  JobRun x;
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
  p.duration_s = 4;
  x.drive = sim::simulateCached(p, ROADSLAM_SIM_CACHE);
  x.dir = runfolder::test::freshDir("map-job");
  const std::string ini = x.dir + "-objects.ini";
  runfolder::test::writeText(ini, runfolder::test::readText(std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini") +
                                      "\n[objects]\nenabled = true\n");
  jobs::MapRequest req;
  req.config_path = ini;
  req.input_path = x.drive + "/velodyne.pcap";
  req.out_dir = x.dir;
  req.progress = false;
  x.out = jobs::runMapJob(req);
  return x;
}

void readsBackWhatTheJobHeld(const JobRun& r) {
  const auto folder = runfolder::openMapRun(r.dir);
  EXPECT_EQ(folder.manifest().program, "roadslam-map");
  EXPECT_EQ(folder.manifest().input, r.out.summary["input"].get<std::string>());
  const auto frames = folder.frames();
  ASSERT_EQ(frames.size(), r.out.frames.size());
  ASSERT_GT(frames.size(), 30u);
  for (size_t i = 0; i < frames.size(); ++i) {
    const auto& f = r.out.frames[i];
    EXPECT_EQ(frames[i].index, f.index);
    EXPECT_NEAR(frames[i].stamp_s, f.stamp_s, 1e-6);
    EXPECT_EQ(frames[i].status, odometry::toString(f.status));
    EXPECT_EQ(frames[i].keyframe, f.keyframe);
    EXPECT_NEAR(frames[i].x_m, f.T_world_lidar.translation().x(), 1e-4);
    EXPECT_EQ(frames[i].inliers, f.inliers);
  }
  const auto traj = folder.trajectory();
  const auto rows = runfolder::trajectoryRowOfFrames(frames, traj.size(), r.dir);
  for (size_t i = 0; i < frames.size(); ++i) {
    if (rows[i] < 0) continue;
    const auto k = static_cast<size_t>(rows[i]);
    EXPECT_TRUE(traj.pose(k).isApprox(r.out.T_map_lidar[i], 1e-6));
    EXPECT_TRUE(traj.at(frames[i].stamp_s)->isApprox(r.out.T_map_lidar[i], 1e-6));
  }
  const auto s = folder.mapSummary();
  EXPECT_EQ(s.frames, r.out.frames.size());
  EXPECT_EQ(s.byStatus("ok"), r.out.summary["frames_by_status"].value("ok", 0));
  EXPECT_EQ(s.complete, r.out.summary["complete"].get<bool>());
  EXPECT_TRUE(s.loop_closures.has_value());
}

void theTrajectoryFollowsTheSimulatorsTruth(const JobRun& r) {
  const auto est = runfolder::openMapRun(r.dir).trajectory();
  const auto gt = runfolder::readTrajectory(r.drive + "/gt_trajectory.tum");
  // both start at the lidar's first pose: T_gt_est from the first estimated pose, then compare positions
  const auto g0 = gt.at(est.stamp(0));
  ASSERT_TRUE(g0);
  const Eigen::Isometry3d T_gt_est = *g0 * est.pose(0).inverse();
  size_t compared = 0;
  for (size_t k = 0; k < est.size(); ++k) {
    const auto g = gt.at(est.stamp(k), 0.5);
    if (!g) continue;
    ++compared;
    EXPECT_LT(((T_gt_est * est.pose(k)).translation() - g->translation()).norm(), 0.5) << "at " << est.stamp(k);
  }
  EXPECT_GT(compared, est.size() * 9 / 10);
}

void tracksAndObjectsAsWritten(const JobRun& r) {
  const auto folder = runfolder::openMapRun(r.dir);
  ASSERT_TRUE(folder.has(runfolder::kTracksCsv));
  const auto tracks = folder.tracks();
  const auto objects = folder.objects();
  // independent count: the data lines of the files
  auto lines = [](const std::string& p) {
    const std::string t = runfolder::test::readText(p);
    return static_cast<size_t>(std::count(t.begin(), t.end(), '\n')) - 1;
  };
  EXPECT_EQ(tracks.size(), lines(folder.path(runfolder::kTracksCsv)));
  EXPECT_EQ(objects.size(), lines(folder.path(runfolder::kObjectsCsv)));
  EXPECT_EQ(objects.size(), r.out.summary["objects"]["objects"].get<size_t>());
  EXPECT_GT(objects.size(), 0u);
  for (const auto& o : objects) EXPECT_LT(o.frame, r.out.frames.size());
  EXPECT_NO_THROW(folder.tracksEnded());
}

}  // namespace

TEST(MapJobFolder, ReadsBackTheJobsFramesTrajectoryTracksAndObjects) {
  const JobRun r = runJob();
  {
    SCOPED_TRACE("frames, trajectory and summary as the job held them");
    readsBackWhatTheJobHeld(r);
  }
  {
    SCOPED_TRACE("trajectory against the simulator's truth");
    theTrajectoryFollowsTheSimulatorsTruth(r);
  }
  {
    SCOPED_TRACE("tracks and objects as written");
    tracksAndObjectsAsWritten(r);
  }
}
