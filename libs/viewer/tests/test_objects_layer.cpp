// The objects over a replay: a map folder's tracks.csv and objects.csv, written by libs/objects' own
// writers, read back and rendered headless (CFBORender) from the top; the pixels of each colour must lie
// where the camera's projection puts the tracks' boxes and arrows, and nowhere else.
#include <gtest/gtest.h>

#include <mrpt/img/CImage.h>
#include <mrpt/opengl/COpenGLScene.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "roadslam/objects/stage.h"
#include "roadslam/runfolder/run_folder.h"
#include "roadslam/sources/recording.h"
#include "boxroom.h"
#include "roadslam/viewer/render.h"
#include "roadslam/viewer/replay.h"

using namespace roadslam::viewer;
namespace fs = std::filesystem;

namespace {

using roadslam::viewer::test::boxroomRawlog;
using roadslam::viewer::test::tempDir;

roadslam::objects::Track track(int id, bool moving, double x, double y, double vx, double vy) {
  roadslam::objects::Track t;
  t.id = id, t.state = roadslam::objects::TrackState::Confirmed, t.moving = moving;
  t.x << x, y, vx, vy;
  t.heading = 0, t.length = 4.5, t.width = 1.8, t.z_min = -1.9, t.z_max = -0.4;
  return t;
}

/// A map folder at the identity pose: a moving car (id 7) 12 m ahead driving +x at 8 m/s, a parked
/// one (id 3) behind on the left, and an object no track took on the right, at \p t; the moving car
/// 8 m farther one sweep later (at \p t + 0.1 s, not the sweep shown).
void writeFolder(const fs::path& dir, double t) {
  fs::create_directories(dir);
  roadslam::datasets::Trajectory poses;
  for (int k = -5; k <= 5; ++k) poses.stamps_s.push_back(t + 0.1 * k), poses.poses.push_back(Eigen::Isometry3d::Identity());
  roadslam::runfolder::writeMapRun(dir.string(), roadslam::runfolder::mapRunOfTrajectory(poses, "test"));
  roadslam::objects::ObjectsFrame f;
  f.tracks = {track(7, true, 12, 0, 8, 0), track(3, false, -10, 6, 0, 0)};
  roadslam::objects::Object o;
  o.box = {{0, -12}, 0, 2.0, 1.0, -1.9, -0.9};
  o.points = 40;
  f.objects = {o};
  f.object_track = {-1};
  roadslam::objects::ObjectsFrame later;
  later.tracks = {track(7, true, 20, 0, 8, 0)};
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  std::ofstream(dir / "tracks.csv") << roadslam::objects::tracksCsvHeader() << roadslam::objects::tracksCsvRows(0, t, f)
                                    << roadslam::objects::tracksCsvRows(1, t + 0.1, later);
  std::ofstream(dir / "objects.csv") << roadslam::objects::objectsCsvHeader() << roadslam::objects::objectsCsvRows(0, t, I, f);
}

struct Px {
  double u, v;
};

/// Pixels of the hue of \p c in \p img: lines are shaded and blended at their edges, so a pixel matches
/// when it is bright enough (> 70) and its channels over its brightest are \p c's within 0.12.
std::vector<Px> pixelsOf(const mrpt::img::CImage& img, const unsigned char c[3]) {
  const double cm = std::max({c[0], c[1], c[2]});
  std::vector<Px> out;
  for (int y = 0; y < int(img.getHeight()); ++y)
    for (int x = 0; x < int(img.getWidth()); ++x) {
      const auto* p = img.ptr<uint8_t>(x, y);  // BGR
      const double m = std::max({p[0], p[1], p[2]});
      if (m <= 70) continue;
      bool same = true;
      for (int k = 0; k < 3; ++k) same = same && std::abs(p[2 - k] / m - c[k] / cm) <= 0.12;
      if (same) out.push_back({double(x), double(y)});
    }
  return out;
}

}  // namespace

TEST(ViewerObjects, TracksCsvReadsBackWhatTheObjectsStageWrote) {
  const fs::path dir = tempDir() / "read";
  writeFolder(dir, 100.0);
  const auto frames = readObjectsFolder(dir.string());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_NEAR(frames[0].stamp_s, 100.0, 1e-6);
  ASSERT_EQ(frames[0].boxes.size(), 3u);  // two tracks and the untracked object
  const ObjectBox& m = frames[0].boxes[0];
  EXPECT_EQ(m.track_id, 7);
  EXPECT_TRUE(m.moving);
  EXPECT_NEAR(m.box.centre_m.x(), 12, 1e-3);
  EXPECT_NEAR(m.vx_mps, 8, 1e-3);
  EXPECT_NEAR(m.box.length_m, 4.5, 1e-3);
  EXPECT_EQ(frames[0].boxes[1].track_id, 3);
  EXPECT_FALSE(frames[0].boxes[1].moving);
  EXPECT_EQ(frames[0].boxes[2].track_id, -1);
  EXPECT_NEAR(frames[0].boxes[2].box.centre_m.y(), -12, 1e-3);
  EXPECT_NEAR(frames[1].boxes[0].box.centre_m.x(), 20, 1e-3);

  std::ofstream(dir / "tracks.csv", std::ios::app) << "2,100.2,9,oops\n";
  try {
    readObjectsFolder(dir.string());
    FAIL() << "a malformed row must be an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("tracks.csv:5"), std::string::npos) << e.what();
  }
}

TEST(ViewerObjects, BoxesIdsAndArrowsAreWhereTheTracksAre) {
  double t_sweep = 0;
  {
    ViewerInputs in;
    in.recording = boxroomRawlog();
    ViewerModel model(in);
    Replay replay(model);
    replay.seek(model.startTime() + 0.25);
    ASSERT_TRUE(replay.currentSweep()) << replay.lastError();
    t_sweep = replay.currentSweep()->stamp_s;
  }
  const fs::path dir = tempDir() / "map";
  writeFolder(dir, t_sweep + 0.05);  // the tracks' time: mid-sweep, as roadslam-map writes it
  ViewerInputs in;
  in.recording = boxroomRawlog();
  in.map_dir = dir.string();
  ViewerModel model(in);
  Replay replay(model);
  replay.seek(t_sweep + 0.01);
  SceneOptions& o = replay.options();
  o.camera = CameraMode::TopDown;
  o.top_height_m = 60;
  o.show_sweep = o.show_trajectory = o.show_keyframes = o.hud = o.plots = false;

  const int W = 640, H = 480;
  PngRenderer renderer(W, H);
  const std::string png = (tempDir() / "objects.png").string();
  mrpt::opengl::COpenGLScene scene;
  const CameraView view = buildScene(model, replay.state(), o, scene);
  renderer.render(scene, view, png);
  mrpt::img::CImage img;
  ASSERT_TRUE(img.loadFromFile(png));

  // Top-down pinhole (MRPT's vertical field of view), map +x right and +y up, the car at the centre;
  // a point at height z is (distance - z) from the eye.
  const double fov = scene.getViewport("main")->getCamera().getProjectiveFOVdeg() * M_PI / 180.0;
  const double f_px = 0.5 * H / std::tan(0.5 * fov);
  auto project = [&](double x, double y, double z) { return Px{0.5 * W + x * f_px / (view.distance_m - z), 0.5 * H - y * f_px / (view.distance_m - z)}; };
  // Every pixel of a colour inside the projection of [x0, x1] x [y0, y1] (z from -1.9 to -0.4 m) grown by 3 px.
  auto inside = [&](const std::vector<Px>& px, double x0, double x1, double y0, double y1) {
    const Px a = project(x0, y1, -0.4), b = project(x1, y0, -0.4), c = project(x0, y1, -1.9), d = project(x1, y0, -1.9);
    const double u0 = std::min(a.u, c.u) - 3, u1 = std::max(b.u, d.u) + 3, v0 = std::min(a.v, c.v) - 3, v1 = std::max(b.v, d.v) + 3;
    int out = 0;
    for (const Px& p : px) out += p.u < u0 || p.u > u1 || p.v < v0 || p.v > v1;
    return out;
  };
  auto near = [&](const std::vector<Px>& px, const Px& at, double r) {
    int n = 0;
    for (const Px& p : px) n += std::hypot(p.u - at.u, p.v - at.v) <= r;
    return n;
  };

  const auto moving = pixelsOf(img, SceneColors::object_moving);
  const auto parked = pixelsOf(img, SceneColors::object_static);
  const auto untracked = pixelsOf(img, SceneColors::object_untracked);
  ASSERT_GT(moving.size(), 100u);
  ASSERT_GT(parked.size(), 60u);
  ASSERT_GT(untracked.size(), 30u);
  // the moving car: its box (12 +- 2.25, 0 +- 0.9) and its 1 s arrow to x = 20; not where it is a sweep later
  EXPECT_EQ(inside(moving, 9.75, 20.0, -0.9, 0.9), 0);
  EXPECT_GT(near(moving, project(9.75, -0.9, -1.9), 3), 0) << "a corner of the box";
  EXPECT_GT(near(moving, project(14.25, 0.9, -0.4), 3), 0) << "the opposite corner, on the roof";
  EXPECT_GT(near(moving, project(20.0, 0.0, -0.4), 3), 0) << "the arrow's tip: 1 s at 8 m/s";
  EXPECT_GT(near(moving, project(12.0, 0.0, -0.4), 8), 0) << "the id above the box";
  // the parked car: its box only (no arrow at 0 m/s); the untracked object: its box
  EXPECT_EQ(inside(parked, -12.25, -7.75, 5.1, 6.9), 0);
  EXPECT_GT(near(parked, project(-12.25, 5.1, -1.9), 3), 0);
  EXPECT_EQ(inside(untracked, -1.0, 1.0, -12.5, -11.5), 0);
  EXPECT_GT(near(untracked, project(1.0, -11.5, -0.9), 3), 0);

  // with the layer off (key o), none of its colours is on screen (the checks above can fail)
  ASSERT_TRUE(replay.handleKey(*parseKey("o")));
  EXPECT_FALSE(o.show_objects);
  const std::string off = (tempDir() / "objects_off.png").string();
  mrpt::opengl::COpenGLScene scene_off;
  renderer.render(scene_off, buildScene(model, replay.state(), o, scene_off), off);
  ASSERT_TRUE(img.loadFromFile(off));
  EXPECT_TRUE(pixelsOf(img, SceneColors::object_moving).empty());
  EXPECT_TRUE(pixelsOf(img, SceneColors::object_static).empty());
}
