// The viewer's scene rendered headless (CFBORender) on the bundled box-room capture: the same
// picture twice, the trajectory's colour where the camera puts it, the sweep's points on screen,
// and the replay's shortcuts moving through the recording.
#include <gtest/gtest.h>

#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <thread>

#include "roadslam/mapping/maps.h"
#include "roadslam/runfolder/run_folder.h"
#include "roadslam/sources/recording.h"
#include "boxroom.h"
#include "roadslam/viewer/render.h"
#include "roadslam/viewer/replay.h"

namespace {
/// The files of a map folder holding poses at \p stamps_s at positions \p xy (written with runfolder's writer, run.json too).
roadslam::runfolder::MapRunFiles poseFolder(const std::vector<double>& stamps_s, const std::vector<Eigen::Vector2d>& xy) {
  roadslam::datasets::Trajectory t;
  for (size_t i = 0; i < stamps_s.size(); ++i) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() << xy[i].x(), xy[i].y(), 0;
    t.stamps_s.push_back(stamps_s[i]);
    t.poses.push_back(T);
  }
  return roadslam::runfolder::mapRunOfTrajectory(t, "test");
}
}  // namespace

using namespace roadslam::viewer;
namespace fs = std::filesystem;

namespace {

using roadslam::viewer::test::boxroomRawlog;
using roadslam::viewer::test::tempDir;

// The trajectory's magenta (SceneColors::trajectory), also where lines are blended with the
// background: red and blue alike, no green. The jet colour map of the sweep never gives that hue.
bool isTrajectoryHue(int r, int g, int b) { return r > 100 && b > 100 && g < 40 && std::abs(r - b) < 30; }

std::string slurp(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

struct Counts {
  int magenta_left = 0, magenta_right = 0, coloured = 0;
};

// Trajectory pixels (exactly SceneColors::trajectory) on each side of the image centre, and pixels
// that are neither background, text white nor grey (the jet-coloured sweep).
Counts countPixels(const std::string& png) {
  mrpt::img::CImage img;
  EXPECT_TRUE(img.loadFromFile(png));
  Counts c;
  const int w = int(img.getWidth()), h = int(img.getHeight());
  for (int y = 30; y < h; ++y)  // below the HUD line
    for (int x = 0; x < w; ++x) {
      const auto* px = img.ptr<uint8_t>(x, y);  // BGR
      const int b = px[0], g = px[1], r = px[2];
      if (isTrajectoryHue(r, g, b)) {  // the keyframe marker at the car (the centre) is 5 px wide
        if (x < w / 2 - 8) ++c.magenta_left;
        if (x > w / 2 + 8) ++c.magenta_right;
      }
      const int mx = std::max({r, g, b}), mn = std::min({r, g, b});
      if (mx - mn > 60 && !isTrajectoryHue(r, g, b)) ++c.coloured;
    }
  return c;
}

}  // namespace

TEST(ViewerRender, SameSceneGivesTheSamePictureWithTrajectoryAndSweep) {
  ViewerInputs in;
  in.recording = boxroomRawlog();
  ViewerModel model(in);
  ASSERT_GE(model.recording().size(), 6u);
  // a frame result per sweep, streamed in as a live odometry would: the car drove 10 m along +x up
  // to the box room (the sweeps are drawn at the last pose)
  const double t0 = model.startTime();
  for (int k = 0; k <= 20; ++k) {
    ViewerFrame f;
    f.stamp_s = t0 - 2.0 + 0.1 * k;
    f.T_map_lidar.translation() = Eigen::Vector3d(-10.0 + 0.5 * k, 0, 0);
    f.keyframe = k % 5 == 0;
    model.appendFrame(f);
  }
  Replay replay(model);
  replay.options().camera = CameraMode::TopDown;
  replay.options().top_height_m = 40;
  replay.seek(t0 + 0.25);
  ASSERT_TRUE(replay.currentSweep()) << replay.lastError();
  EXPECT_GT(replay.currentSweep()->points.size(), 10000u);  // both VLP-16 firings decoded

  PngRenderer renderer(480, 360);
  const std::string a = (tempDir() / "a.png").string(), b = (tempDir() / "b.png").string();
  renderCurrent(replay, renderer, a);
  renderCurrent(replay, renderer, b);
  ASSERT_TRUE(fs::exists(a));
  EXPECT_EQ(slurp(a), slurp(b)) << "the same scene must render to the same bytes";

  // top-down, map north up: the path came from -x, i.e. from the left of the picture's centre
  const Counts c = countPixels(a);
  EXPECT_GT(c.magenta_left, 50);
  EXPECT_EQ(c.magenta_right, 0);
  EXPECT_GT(c.coloured, 2500) << "the sweep's points";

  // without the sweep and the trajectory, neither is on screen (the counts above can fail)
  replay.options().show_trajectory = replay.options().show_keyframes = false;
  mrpt::opengl::COpenGLScene scene;
  SceneState empty = replay.state();
  empty.sweep = nullptr;
  const CameraView view = buildScene(model, empty, replay.options(), scene);
  const std::string e = (tempDir() / "empty.png").string();
  renderer.render(scene, view, e);
  const Counts ce = countPixels(e);
  EXPECT_EQ(ce.magenta_left + ce.magenta_right, 0);
  EXPECT_GT(c.coloured - ce.coloured, 2000) << "the sweep adds coloured pixels (the car's axes stay)";
}

TEST(ViewerReplay, ShortcutsStepPlayAndClamp) {
  ViewerInputs in;
  in.recording = boxroomRawlog();
  ViewerModel model(in);
  Replay replay(model);
  const auto first = replay.currentObservation();
  ASSERT_TRUE(first);
  EXPECT_TRUE(replay.handleKey(*parseKey("right")));
  const auto second = replay.currentObservation();
  ASSERT_TRUE(second);
  EXPECT_GT(*second, *first);
  EXPECT_EQ(model.recording().className(*second), "CObservationVelodyneScan");
  replay.handleKey(*parseKey("left"));
  EXPECT_EQ(replay.currentObservation(), first);
  replay.handleKey(*parseKey("end"));
  EXPECT_DOUBLE_EQ(replay.time(), model.endTime());
  replay.handleKey(*parseKey("home"));
  EXPECT_DOUBLE_EQ(replay.time(), model.startTime());
  for (int i = 0; i < 10; ++i) replay.handleKey(*parseKey("+"));
  EXPECT_DOUBLE_EQ(replay.speed(), Replay::kMaxSpeed);
  for (int i = 0; i < 10; ++i) replay.handleKey(*parseKey("-"));
  EXPECT_DOUBLE_EQ(replay.speed(), Replay::kMinSpeed);
  replay.setSpeed(2.0);
  replay.handleKey(*parseKey("space"));
  EXPECT_TRUE(replay.playing());
  replay.advance(0.1);
  EXPECT_NEAR(replay.time(), model.startTime() + 0.2, 1e-9);
  replay.advance(100);
  EXPECT_FALSE(replay.playing()) << "stops at the end";
  replay.handleKey(*parseKey("c"));
  EXPECT_EQ(replay.options().color_by, ColorBy::Intensity);
  EXPECT_FALSE(parseKey("F13"));
  const std::string d = replay.details(*second);
  EXPECT_NE(d.find("rings       16"), std::string::npos) << d;
  EXPECT_NE(d.find("VELODYNE"), std::string::npos) << d;
}

TEST(ViewerModel, MapFolderTimesOutsideTheRecordingAreNamed) {
  const fs::path dir = tempDir() / "map_elsewhere";
  fs::create_directories(dir);
  roadslam::runfolder::writeMapRun(dir.string(), poseFolder({100.0, 100.1}, {{0, 0}, {1, 0}}));
  ViewerInputs in;
  in.recording = boxroomRawlog();
  in.map_dir = dir.string();
  ViewerModel model(in);
  ASSERT_EQ(model.frames().size(), 2u);
  ASSERT_FALSE(model.warnings().empty());
  EXPECT_NE(model.warnings().back().find("do not overlap the recording"), std::string::npos) << model.warnings().back();
}

// A map folder as roadslam-map writes it (trajectory.tum, frames.csv, summary.json loops, map.ply by
// the mapping library's own writer): frames with status and keyframes, the loop edge between its two
// frames, the point map decimated per voxel; the loop drawn in its colour once its time has come.
TEST(ViewerModel, MapFolderLoopsKeyframesAndDecimatedPointMap) {
  const fs::path dir = tempDir() / "map_loop";
  fs::create_directories(dir);
  ViewerInputs in;
  in.recording = boxroomRawlog();
  const double t0 = ViewerModel(in).startTime();
  {  // a square drive of 4 frames back to the start: frame 3 closes a loop onto frame 0
    const double xy[4][2] = {{0, 0}, {8, 0}, {8, 8}, {0.5, 0.5}};
    std::vector<double> st;
    std::vector<Eigen::Vector2d> p;
    for (int i = 0; i < 4; ++i) st.push_back(t0 + 0.1 * i), p.emplace_back(xy[i][0], xy[i][1]);
    auto files = poseFolder(st, p);
    for (int i = 0; i < 4; ++i) files.frames[size_t(i)].status = i == 2 ? "degenerate" : "ok", files.frames[size_t(i)].keyframe = i % 2 == 0;
    auto s = roadslam::runfolder::mapSummaryFromJson(files.summary, "test");
    s.loops_accepted.push_back({3, 0, 2, 0, 0.1, 0.8, 0.2, "accepted"});
    files.summary = roadslam::runfolder::mapSummaryJson(s);
    roadslam::runfolder::writeMapRun(dir.string(), files);
    std::vector<Eigen::Vector3f> pts;
    for (int i = 0; i < 1000; ++i) pts.emplace_back(0.01f * float(i), 0.f, 0.f);  // 10 m of points 1 cm apart
    roadslam::mapping::writePly((dir / "map.ply").string(), pts);
  }
  in.map_dir = dir.string();
  in.map_voxel_m = 0.5;
  ViewerModel model(in);
  ASSERT_EQ(model.frames().size(), 4u);
  EXPECT_EQ(model.frames()[2].status, "degenerate");
  EXPECT_TRUE(model.frames()[0].keyframe);
  EXPECT_FALSE(model.frames()[1].keyframe);
  ASSERT_EQ(model.loops().size(), 1u);
  EXPECT_EQ(model.loops()[0].query, Eigen::Vector3d(0.5, 0.5, 0));
  EXPECT_EQ(model.loops()[0].match, Eigen::Vector3d(0, 0, 0));
  EXPECT_NEAR(model.loops()[0].stamp_s, t0 + 0.3, 1e-6);
  EXPECT_EQ(model.mapPoints().size(), 20u);  // 10 m at one point per 0.5 m voxel
  EXPECT_TRUE(model.warnings().empty() || model.warnings()[0].find("overlap") == std::string::npos);

  Replay replay(model);
  replay.options().camera = CameraMode::TopDown;
  replay.options().top_height_m = 20;
  replay.options().show_sweep = false;  // the box room's walls are orange in the jet colour map
  PngRenderer renderer(320, 240);
  const auto loopPixels = [&](double t) {
    replay.seek(t);
    const std::string png = (tempDir() / "loop.png").string();
    renderCurrent(replay, renderer, png);
    mrpt::img::CImage img;
    EXPECT_TRUE(img.loadFromFile(png));
    int n = 0;
    for (int y = 30; y < 240; ++y)
      for (int x = 0; x < 320; ++x) {
        const auto* px = img.ptr<uint8_t>(x, y);  // BGR; the loop is orange (255, 140, 0)
        if (px[2] > 200 && px[1] > 90 && px[1] < 180 && px[0] < 40) ++n;
      }
    return n;
  };
  EXPECT_EQ(loopPixels(t0 + 0.15), 0) << "before the loop closed";
  EXPECT_GT(loopPixels(t0 + 0.35), 0) << "after it";
}

// Frame results streamed in from another thread (an odometry beside the replay) reach the model on
// the drawing thread, in time order, and count as "so far" by their stamps.
TEST(ViewerModel, FramesPostedFromAnotherThreadAreTakenInOrder) {
  ViewerInputs in;
  in.recording = boxroomRawlog();
  ViewerModel model(in);
  const double t0 = model.startTime();
  std::thread producer([&] {
    for (int k = 9; k >= 0; --k) {  // out of order on purpose
      ViewerFrame f;
      f.stamp_s = t0 + 0.05 * k;
      f.T_map_lidar.translation().x() = k;
      model.postFrame(f);
    }
  });
  producer.join();
  EXPECT_TRUE(model.frames().empty()) << "nothing before the drawing thread takes them";
  EXPECT_EQ(model.takePosted(), 10u);
  ASSERT_EQ(model.frames().size(), 10u);
  for (std::size_t i = 0; i < 10; ++i) EXPECT_EQ(model.frames()[i].T_map_lidar.translation().x(), double(i));
  EXPECT_EQ(model.framesUpTo(t0 + 0.12), 3u);
  EXPECT_EQ(model.takePosted(), 0u);
}

// A recording without an index opens while it is indexed in the background; the checks that need
// all of it (the map folder's times against the recording's) wait for the end of the indexing.
// Oracle: the index built in one go.
TEST(ViewerModel, IndexedInTheBackgroundEndsAsTheWholeRecording) {
  const fs::path rec = tempDir() / "long.rawlog", dir = tempDir() / "map_elsewhere_long";
  {
    mrpt::io::CFileGZOutputStream f(rec.string());
    auto ar = mrpt::serialization::archiveFrom(f);
    for (int i = 0; i < 20000; ++i) {  // 20000 odometry records, 200 s at 100 Hz
      mrpt::obs::CObservationOdometry o;
      o.sensorLabel = "CAN_ODOMETRY";
      o.timestamp = mrpt::Clock::fromDouble(1000.0 + 0.01 * i);
      o.odometry = mrpt::poses::CPose2D(0.1 * i, 0, 0);
      ar << o;
    }
  }
  fs::remove(roadslam::rawlog::RawlogIndex::sidecarPath(rec.string()));
  fs::create_directories(dir);
  roadslam::runfolder::writeMapRun(dir.string(), poseFolder({100.0, 100.1}, {{0, 0}, {1, 0}}));
  ViewerInputs in;
  in.recording = rec.string();
  in.map_dir = dir.string();
  ViewerModel model(in);
  ASSERT_GT(model.recording().size(), 0u);
  const auto overlapWarned = [&] {
    for (const auto& w : model.warnings())
      if (w.find("do not overlap the recording") != std::string::npos) return true;
    return false;
  };
  const bool was_indexing = model.indexing();
  if (was_indexing) {
    EXPECT_FALSE(overlapWarned()) << "checked against a part of the recording";
  }
  for (int k = 0; model.indexing() && k < 20000; ++k) {
    model.poll();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_FALSE(model.indexing());
  EXPECT_EQ(model.recording().size(), 20000u);
  EXPECT_DOUBLE_EQ(model.endTime(), 1000.0 + 0.01 * 19999);
  EXPECT_TRUE(overlapWarned());
  ASSERT_NE(model.rawlog(), nullptr);
  EXPECT_TRUE(fs::exists(roadslam::rawlog::RawlogIndex::sidecarPath(rec.string())));
}
