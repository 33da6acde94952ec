#include "roadslam/viewer/objects_layer.h"

#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CText.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>

#include "roadslam/runfolder/objects_csv.h"
#include "roadslam/viewer/scene.h"

namespace roadslam::viewer {
namespace {

constexpr double kArrowMinSpeed_mps = 0.5;  // slower tracks get no arrow (a parked car's filter noise)
constexpr double kArrowHead_m = 0.8;
constexpr double kArrowHeadAngle_rad = 25.0 * M_PI / 180.0;

mrpt::img::TColor colourOf(const ObjectBox& b) {
  const unsigned char* c = b.track_id < 0 ? SceneColors::object_untracked
                           : b.moving     ? SceneColors::object_moving
                                          : SceneColors::object_static;
  return {c[0], c[1], c[2], 255};
}

void addBox(const OrientedBox& b, mrpt::opengl::CSetOfLines& l) {
  const auto fl_fr_rr_rl = b.corners();
  // counter-clockwise from the rear right corner: the scene's line order, which a render's pixels depend on
  const std::array<Eigen::Vector2d, 4> c = {fl_fr_rr_rl[2], fl_fr_rr_rl[1], fl_fr_rr_rl[0], fl_fr_rr_rl[3]};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d &p = c[k], &q = c[(k + 1) % 4];
    l.appendLine(p.x(), p.y(), b.z_min_m, q.x(), q.y(), b.z_min_m);
    l.appendLine(p.x(), p.y(), b.z_max_m, q.x(), q.y(), b.z_max_m);
    l.appendLine(p.x(), p.y(), b.z_min_m, p.x(), p.y(), b.z_max_m);
  }
}

void addArrow(const ObjectBox& b, mrpt::opengl::CSetOfLines& l) {
  const double speed = std::hypot(b.vx_mps, b.vy_mps);
  if (speed < kArrowMinSpeed_mps) return;
  const double x = b.box.centre_m.x(), y = b.box.centre_m.y();
  const double z = b.box.z_max_m, tx = x + b.vx_mps, ty = y + b.vy_mps;  // where it is in 1 s
  l.appendLine(x, y, z, tx, ty, z);
  const double back = std::atan2(-b.vy_mps, -b.vx_mps);
  for (double side : {-1.0, 1.0}) {
    const double a = back + side * kArrowHeadAngle_rad;
    l.appendLine(tx, ty, z, tx + kArrowHead_m * std::cos(a), ty + kArrowHead_m * std::sin(a), z);
  }
}

}  // namespace

std::vector<ObjectBoxes> readObjectsFolder(const std::string& dir) {
  std::map<double, ObjectBoxes> by_stamp;
  const std::string tracks = dir + "/" + runfolder::kTracksCsv, objects = dir + "/" + runfolder::kObjectsCsv;
  if (!std::filesystem::exists(tracks)) return {};
  for (const runfolder::TrackRow& r : runfolder::readTracksCsv(tracks)) {
    ObjectBox b;
    b.track_id = r.track_id;
    b.moving = r.moving;
    b.box = r.box;
    b.vx_mps = r.vx, b.vy_mps = r.vy;
    by_stamp[r.stamp_s].stamp_s = r.stamp_s;
    by_stamp[r.stamp_s].boxes.push_back(b);
  }
  if (std::filesystem::exists(objects)) {
    for (const runfolder::ObjectRow& r : runfolder::readObjectsCsv(objects)) {
      if (r.track_id >= 0) continue;  // drawn as its track
      ObjectBox b;
      b.box = r.box;
      by_stamp[r.stamp_s].stamp_s = r.stamp_s;
      by_stamp[r.stamp_s].boxes.push_back(b);
    }
  }
  std::vector<ObjectBoxes> out;
  out.reserve(by_stamp.size());
  for (auto& [t, f] : by_stamp) out.push_back(std::move(f));
  return out;
}

void addObjectBoxes(const ObjectBoxes& f, mrpt::opengl::COpenGLScene& scene) {
  using mrpt::opengl::CSetOfLines;
  for (const ObjectBox& b : f.boxes) {
    auto lines = CSetOfLines::Create();
    addBox(b.box, *lines);
    addArrow(b, *lines);
    lines->setColor_u8(colourOf(b));
    lines->setLineWidth(2.f);
    lines->enableAntiAliasing(false);  // exact colours: tests find the boxes by colour
    scene.insert(lines);
    if (b.track_id < 0) continue;
    auto label = mrpt::opengl::CText::Create(std::to_string(b.track_id));
    label->setLocation(b.box.centre_m.x(), b.box.centre_m.y(), b.box.z_max_m + 0.5);
    label->setColor_u8(colourOf(b));
    scene.insert(label);
  }
}

}  // namespace roadslam::viewer
