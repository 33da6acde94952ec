#include "roadslam/viewer/objects_layer.h"

#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CText.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "roadslam/viewer/scene.h"

namespace roadslam::viewer {
namespace {

constexpr double kArrowMinSpeed_mps = 0.5;  // slower tracks get no arrow (a parked car's filter noise)
constexpr double kArrowHead_m = 0.8;
constexpr double kArrowHeadAngle_rad = 25.0 * M_PI / 180.0;

/// A CSV file read by column name; number() throws naming the file and line.
class Csv {
 public:
  explicit Csv(const std::string& path) : path_(path), in_(path) {
    std::string header;
    if (!std::getline(in_, header)) throw std::runtime_error(path + ": empty, no header line");
    std::size_t c = 0;
    for (const auto& name : split(header)) col_[name] = c++;
  }
  bool next() {
    std::string line;
    if (!std::getline(in_, line)) return false;
    ++line_;
    row_ = split(line);
    return true;
  }
  double number(const std::string& name) const {
    const auto it = col_.find(name);
    if (it == col_.end()) throw std::runtime_error(path_ + ": no column '" + name + "'");
    const std::string cell = it->second < row_.size() ? row_[it->second] : "";
    char* end = nullptr;
    const double v = std::strtod(cell.c_str(), &end);
    if (cell.empty() || *end != '\0' || !std::isfinite(v))
      throw std::runtime_error(path_ + ":" + std::to_string(line_) + ": column '" + name + "' is not a number: '" + cell + "'");
    return v;
  }

 private:
  static std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) out.push_back(cell);
    return out;
  }
  std::string path_;
  std::ifstream in_;
  std::map<std::string, std::size_t> col_;
  std::vector<std::string> row_;
  std::size_t line_ = 1;  // lines read, the header included
};

mrpt::img::TColor colourOf(const ObjectBox& b) {
  const unsigned char* c = b.track_id < 0 ? SceneColors::object_untracked
                           : b.moving     ? SceneColors::object_moving
                                          : SceneColors::object_static;
  return {c[0], c[1], c[2], 255};
}

void addBox(const ObjectBox& b, mrpt::opengl::CSetOfLines& l) {
  const double c = std::cos(b.yaw_rad), s = std::sin(b.yaw_rad);
  double cx[4], cy[4];
  for (int k = 0; k < 4; ++k) {
    const double u = (k == 0 || k == 3 ? -0.5 : 0.5) * b.length_m, v = (k < 2 ? -0.5 : 0.5) * b.width_m;
    cx[k] = b.x + c * u - s * v, cy[k] = b.y + s * u + c * v;
  }
  for (int k = 0; k < 4; ++k) {
    const int n = (k + 1) % 4;
    l.appendLine(cx[k], cy[k], b.z_min_m, cx[n], cy[n], b.z_min_m);
    l.appendLine(cx[k], cy[k], b.z_max_m, cx[n], cy[n], b.z_max_m);
    l.appendLine(cx[k], cy[k], b.z_min_m, cx[k], cy[k], b.z_max_m);
  }
}

void addArrow(const ObjectBox& b, mrpt::opengl::CSetOfLines& l) {
  const double speed = std::hypot(b.vx_mps, b.vy_mps);
  if (speed < kArrowMinSpeed_mps) return;
  const double z = b.z_max_m, tx = b.x + b.vx_mps, ty = b.y + b.vy_mps;  // where it is in 1 s
  l.appendLine(b.x, b.y, z, tx, ty, z);
  const double back = std::atan2(-b.vy_mps, -b.vx_mps);
  for (double side : {-1.0, 1.0}) {
    const double a = back + side * kArrowHeadAngle_rad;
    l.appendLine(tx, ty, z, tx + kArrowHead_m * std::cos(a), ty + kArrowHead_m * std::sin(a), z);
  }
}

}  // namespace

std::vector<ObjectBoxes> readObjectsFolder(const std::string& dir) {
  std::map<double, ObjectBoxes> by_stamp;
  const std::string tracks = dir + "/tracks.csv", objects = dir + "/objects.csv";
  if (!std::filesystem::exists(tracks)) return {};
  for (Csv csv(tracks); csv.next();) {
    ObjectBox b;
    b.track_id = static_cast<int>(csv.number("track_id"));
    b.moving = csv.number("moving") != 0;
    b.x = csv.number("x"), b.y = csv.number("y"), b.yaw_rad = csv.number("heading_rad");
    b.length_m = csv.number("length_m"), b.width_m = csv.number("width_m");
    b.z_min_m = csv.number("z_min"), b.z_max_m = csv.number("z_max");
    b.vx_mps = csv.number("vx"), b.vy_mps = csv.number("vy");
    const double t = csv.number("stamp_s");
    by_stamp[t].stamp_s = t;
    by_stamp[t].boxes.push_back(b);
  }
  if (std::filesystem::exists(objects)) {
    for (Csv csv(objects); csv.next();) {
      if (csv.number("track_id") >= 0) continue;  // drawn as its track
      ObjectBox b;
      b.x = csv.number("cx"), b.y = csv.number("cy"), b.yaw_rad = csv.number("yaw_rad");
      b.length_m = csv.number("length_m"), b.width_m = csv.number("width_m");
      b.z_min_m = csv.number("z_min"), b.z_max_m = csv.number("z_max");
      const double t = csv.number("stamp_s");
      by_stamp[t].stamp_s = t;
      by_stamp[t].boxes.push_back(b);
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
    addBox(b, *lines);
    addArrow(b, *lines);
    lines->setColor_u8(colourOf(b));
    lines->setLineWidth(2.f);
    lines->enableAntiAliasing(false);  // exact colours: tests find the boxes by colour
    scene.insert(lines);
    if (b.track_id < 0) continue;
    auto label = mrpt::opengl::CText::Create(std::to_string(b.track_id));
    label->setLocation(b.x, b.y, b.z_max_m + 0.5);
    label->setColor_u8(colourOf(b));
    scene.insert(label);
  }
}

}  // namespace roadslam::viewer
