#include "roadslam/viewer/scene.h"

#include "roadslam/viewer/objects_layer.h"
#include "roadslam/viewer/plots.h"

#include <mrpt/img/color_maps.h>
#include <mrpt/opengl/COctoMapVoxels.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CTexturedPlane.h>
#include <mrpt/opengl/stock_objects.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace roadslam::viewer {

namespace {
constexpr double kRad2Deg = 180.0 / M_PI;


mrpt::opengl::CSetOfLines::Ptr polyline(const std::vector<Eigen::Vector3d>& pts, const unsigned char c[3],
                                        float width, bool closed = false) {
  auto l = mrpt::opengl::CSetOfLines::Create();
  for (std::size_t i = 1; i < pts.size(); ++i)
    l->appendLine(pts[i - 1].x(), pts[i - 1].y(), pts[i - 1].z(), pts[i].x(), pts[i].y(), pts[i].z());
  if (closed && pts.size() > 2)
    l->appendLine(pts.back().x(), pts.back().y(), pts.back().z(), pts[0].x(), pts[0].y(), pts[0].z());
  l->setColor_u8(rgb(c));
  l->setLineWidth(width);
  l->enableAntiAliasing(false);  // exact colours: readers and tests find the overlays by colour
  return l;
}

float colourIndex(const ScanPoint& p, const Eigen::Vector3d& p_map, const SweepPoints& s,
                  const SceneOptions& o, double z_lidar) {
  switch (o.color_by) {
    case ColorBy::Height:
      return float((p_map.z() - z_lidar - o.height_min_m) / (o.height_max_m - o.height_min_m));
    case ColorBy::Intensity:
      return float(p.intensity / o.intensity_max);
    case ColorBy::Ring:
      return s.has_rings ? float(p.ring) / float(std::max(1, s.rings - 1)) : 0.f;
    case ColorBy::Time:
      return s.span_s > 0 ? float(p.t / s.span_s) : 0.f;
  }
  return 0.f;
}

CameraView cameraFor(const SceneOptions& o, const Eigen::Isometry3d& T_map_lidar) {
  CameraView v;
  v.target = T_map_lidar.translation();
  const Eigen::Vector3d fwd = T_map_lidar.rotation().col(0);
  const double yaw_deg = std::atan2(fwd.y(), fwd.x()) * kRad2Deg;
  switch (o.camera) {
    case CameraMode::Follow:  // behind the car, looking ahead
      v = {v.target, yaw_deg + 180.0, o.follow_elevation_deg, o.follow_distance_m};
      break;
    case CameraMode::TopDown:  // map +y up in the picture
      v = {v.target, -90.0, 89.9, o.top_height_m};
      break;
    case CameraMode::Orbit:
      v = {v.target, o.orbit_azimuth_deg, o.orbit_elevation_deg, o.orbit_distance_m};
      break;
  }
  return v;
}
}  // namespace

const char* toString(ColorBy c) {
  switch (c) {
    case ColorBy::Height: return "height";
    case ColorBy::Intensity: return "intensity";
    case ColorBy::Ring: return "ring";
    case ColorBy::Time: return "time";
  }
  return "?";
}
const char* toString(CameraMode c) {
  switch (c) {
    case CameraMode::Follow: return "follow";
    case CameraMode::TopDown: return "top";
    case CameraMode::Orbit: return "orbit";
  }
  return "?";
}
ColorBy parseColorBy(const std::string& s) {
  for (auto c : {ColorBy::Height, ColorBy::Intensity, ColorBy::Ring, ColorBy::Time})
    if (s == toString(c)) return c;
  throw std::invalid_argument("colour mode '" + s + "': use height, intensity, ring or time");
}
CameraMode parseCameraMode(const std::string& s) {
  for (auto c : {CameraMode::Follow, CameraMode::TopDown, CameraMode::Orbit})
    if (s == toString(c)) return c;
  throw std::invalid_argument("camera '" + s + "': use follow, top or orbit");
}

Eigen::Isometry3d poseAt(const ViewerModel& model, double t_s) {
  if (const auto* f = model.frameNear(t_s)) return f->T_map_lidar;
  const std::size_t n = model.framesUpTo(t_s);
  if (n > 0) return model.frames()[n - 1].T_map_lidar;
  return Eigen::Isometry3d::Identity();
}

CameraView buildScene(const ViewerModel& model, const SceneState& st, const SceneOptions& o,
                      mrpt::opengl::COpenGLScene& scene) {
  using namespace mrpt::opengl;
  scene.clear();
  auto vp = scene.getViewport("main");
  vp->setCustomBackgroundColor(mrpt::img::TColorf(rgb(SceneColors::background)));
  const double t_pose = st.sweep ? st.sweep->stamp_s : st.t_s;
  const Eigen::Isometry3d T_map_lidar = poseAt(model, t_pose);

  if (o.show_map && !model.octoVoxels().empty()) {
    auto voxels = COctoMapVoxels::Create();
    voxels->resizeVoxelSets(1);
    voxels->showVoxels(0, true);
    voxels->showGridLines(false);
    voxels->enableLights(false);
    voxels->setVisualizationMode(COctoMapVoxels::FIXED);
    for (const auto& v : model.octoVoxels())
      voxels->push_back_Voxel(0, COctoMapVoxels::TVoxel({v.x(), v.y(), v.z()}, v.w(), rgb(SceneColors::map)));
    scene.insert(voxels);
  }
  if (o.show_map && model.grid()) {  // on the ground below the car: the grid is 2D
    const GridLayer& g = *model.grid();
    auto plane = CTexturedPlane::Create(float(g.x_min), float(g.x_max), float(g.y_min), float(g.y_max));
    plane->assignImage(g.rgb, g.alpha);
    plane->setLocation(0, 0, T_map_lidar.translation().z() - g.lidar_height_m - 0.05);
    scene.insert(plane);
  }
  if (o.show_map && !model.mapPoints().empty()) {
    auto map = CPointCloud::Create();
    for (const auto& p : model.mapPoints()) map->insertPoint(p.x(), p.y(), p.z());
    map->setColor_u8(rgb(SceneColors::map));
    map->setPointSize(o.map_point_px);
    scene.insert(map);
  }
  if (o.show_ground_truth && !model.groundTruth().empty())
    scene.insert(polyline(model.groundTruth(), SceneColors::ground_truth, 1.5f));

  const std::size_t n = model.framesUpTo(st.t_s + 0.06);  // the frame of the sweep shown counts as "so far"
  if (o.show_trajectory && n > 1) {
    std::vector<Eigen::Vector3d> path;
    path.reserve(n);
    for (std::size_t i = 0; i < n; ++i) path.push_back(model.frames()[i].T_map_lidar.translation());
    scene.insert(polyline(path, SceneColors::trajectory, o.line_px));
  }
  if (o.show_keyframes && n > 0) {
    auto kf = CPointCloud::Create();
    for (std::size_t i = 0; i < n; ++i)
      if (model.frames()[i].keyframe) {
        const auto p = model.frames()[i].T_map_lidar.translation();
        kf->insertPoint(float(p.x()), float(p.y()), float(p.z()));
      }
    kf->setColor_u8(rgb(SceneColors::trajectory));
    kf->setPointSize(5.f);
    scene.insert(kf);
  }
  if (o.show_loops) {
    for (const auto& l : model.loops())
      if (l.stamp_s <= st.t_s + 0.06) scene.insert(polyline({l.query, l.match}, SceneColors::loop, 3.f));
  }
  if (o.show_boundaries)
    if (const auto* b = model.boundaryNear(t_pose)) {
      scene.insert(polyline(b->left, SceneColors::left, 4.f));
      scene.insert(polyline(b->right, SceneColors::right, 4.f));
      scene.insert(polyline(b->free_space, SceneColors::free_space, 1.5f, true));
    }
  if (o.show_objects)
    if (const auto* ob = model.objectsNear(t_pose)) addObjectBoxes(*ob, scene);
  if (st.sweep && o.show_sweep) {
    auto cloud = CPointCloudColoured::Create();
    cloud->reserve(st.sweep->points.size());
    const double z_lidar = T_map_lidar.translation().z();
    for (const auto& p : st.sweep->points) {
      const Eigen::Vector3d q = T_map_lidar * Eigen::Vector3d(p.x, p.y, p.z);
      const float c = std::clamp(colourIndex(p, q, *st.sweep, o, z_lidar), 0.f, 1.f);
      float r, g, b;
      mrpt::img::jet2rgb(c, r, g, b);
      cloud->push_back(float(q.x()), float(q.y()), float(q.z()), r, g, b);
    }
    cloud->setPointSize(o.sweep_point_px);
    scene.insert(cloud);
  }
  auto car = stock_objects::CornerXYZSimple(2.0f, 3.0f);
  car->setPose(mrpt::poses::CPose3D(mrpt::math::CMatrixDouble44(T_map_lidar.matrix())));
  scene.insert(car);
  const CameraView view = cameraFor(o, T_map_lidar);
  auto& cam = vp->getCamera();
  cam.setPointingAt(float(view.target.x()), float(view.target.y()), float(view.target.z()));
  cam.setAzimuthDegrees(float(view.azimuth_deg));
  cam.setElevationDegrees(float(view.elevation_deg));
  cam.setZoomDistance(float(view.distance_m));

  if (o.plots && hasFramePlots(model)) {
    // the strip under the view: the odometry's figures over time, a cursor at the replay's time
    auto strip = scene.createViewport("plots");
    strip->setViewportPosition(0.0, 0.0, 1.0, 0.2);
    strip->setCustomBackgroundColor(mrpt::img::TColorf(15 / 255.f, 15 / 255.f, 20 / 255.f));
    strip->setImageView(framePlots(model, st.t_s, 1280, 144));  // the strip of a 16:9 view
  }
  if (o.hud) {
    char line[256];
    const double t_rel = st.t_s - model.startTime();
    std::snprintf(line, sizeof line, "t %.2f s / %.2f s   obs %s / %zu   %s   colour: %s   camera: %s", t_rel,
                  model.endTime() - model.startTime(),
                  st.observation ? std::to_string(*st.observation).c_str() : "-", model.recording().size(),
                  st.sweep ? (std::to_string(st.sweep->points.size()) + " points").c_str() : "no sweep",
                  toString(o.color_by), toString(o.camera));
    mrpt::opengl::TFontParams font;
    font.vfont_scale = 14.f;
    font.draw_shadow = true;
    vp->addTextMessage(8, -22, line, 0, font);
  }
  return view;
}

}  // namespace roadslam::viewer
