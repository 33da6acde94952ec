#include "roadslam/boundary/output.h"

#include <mrpt/img/CImage.h>

#include <cmath>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"

namespace roadslam::boundary {

const char* toString(FrameStatus s) {
  switch (s) {
    case FrameStatus::Ok: return "ok";
    case FrameStatus::NoPoints: return "no_points";
    case FrameStatus::NoGround: return "no_ground";
  }
  return "?";
}

namespace {

nlohmann::json pts(const std::vector<Vec2>& v) {
  auto a = nlohmann::json::array();
  for (const auto& q : v) a.push_back({std::round(q.x * 1000) / 1000, std::round(q.y * 1000) / 1000});
  return a;
}

nlohmann::json pts3(const std::vector<Vec3>& v) {
  auto a = nlohmann::json::array();
  for (const auto& q : v)
    a.push_back({std::round(q.x * 1000) / 1000, std::round(q.y * 1000) / 1000, std::round(q.z * 1000) / 1000});
  return a;
}

nlohmann::json side(const SideBoundary& s) {
  return {{"found", s.found}, {"reason", s.reason}, {"confidence", s.confidence}, {"coeffs", s.coeffs},
          {"candidates", s.candidates}, {"inliers", s.inliers}, {"bridged_m", s.bridged_m}, {"parallel_m", s.parallel_m}, {"polyline_vehicle", pts(s.polyline_vehicle)},
          {"polyline_map", pts3(s.polyline_map)}};
}

}  // namespace

nlohmann::json toJson(const BoundaryFrame& f, bool with_grid) {
  nlohmann::json j;
  j["index"] = f.index;
  j["stamp_s"] = f.stamp_s;
  j["status"] = toString(f.status);
  j["path_curvature"] = f.path_curvature;
  j["bend_s_m"] = f.bend_s;
  j["bend_curvature"] = f.bend_curvature;
  auto T = nlohmann::json::array();
  const Eigen::Matrix4d M = f.T_map_lidar.matrix();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) T.push_back(M(r, c));
  j["T_map_lidar"] = T;
  j["left"] = side(f.left);
  j["right"] = side(f.right);
  auto obs = nlohmann::json::array();
  for (const auto& o : f.obstacles) {
    obs.push_back({{"center", {o.center.x, o.center.y}}, {"length_m", o.length_m}, {"width_m", o.width_m},
                   {"yaw_rad", o.yaw_rad}, {"max_height_m", o.max_height_m}, {"points", o.points}, {"hull", pts(o.hull)}});
  }
  j["obstacles"] = obs;
  j["free_space"] = pts(f.free_space);
  j["curb_points"] = pts(f.curb_points);
  j["counts"] = {{"points", f.points}, {"ground", f.ground_points}, {"curb", f.curb_count}, {"obstacle", f.obstacle_points}};
  j["ms"] = f.ms;
  if (with_grid) {
    j["grid"] = {{"resolution_m", f.grid.resolution_m}, {"x0_m", f.grid.x0_m}, {"y0_m", f.grid.y0_m},
                 {"nx", f.grid.nx}, {"ny", f.grid.ny}, {"cost", f.grid.cost}};
  }
  return j;
}

void drawTopView(const std::string& png_path, const Scan& scan, const Labelling& lab, const BoundaryFrame& f,
                 double s, const std::vector<Vec2>& curb_map) {
  using mrpt::img::TColor;
  const double x_min = -20, x_max = 45, y_half = 25;  // view [m], vehicle frame
  const int W = static_cast<int>(2 * y_half * s), H = static_cast<int>((x_max - x_min) * s);
  auto px = [&](double y) { return static_cast<int>((y_half - y) * s); };  // y left -> image left
  auto py = [&](double x) { return static_cast<int>((x_max - x) * s); };   // x forward -> image up
  mrpt::img::CImage img(static_cast<unsigned>(W), static_cast<unsigned>(H), mrpt::img::CH_RGB);
  img.filledRectangle(0, 0, W - 1, H - 1, TColor(250, 250, 250));
  for (int g = -20; g <= 20; g += 10) img.line(px(g), 0, px(g), H - 1, TColor(225, 225, 225));
  for (int g = -20; g <= 40; g += 10) img.line(0, py(g), W - 1, py(g), TColor(225, 225, 225));
  const std::vector<Vec2>& fs = f.free_space;
  for (size_t k = 0; k < fs.size(); ++k) {
    const auto& a = fs[k];
    const auto& b = fs[(k + 1) % fs.size()];
    img.line(px(a.y), py(a.x), px(b.y), py(b.x), TColor(60, 190, 60), 2);
  }
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const auto& q = scan.points[i];
    const int u = px(q.y), v = py(q.x);
    if (u < 0 || v < 0 || u >= W || v >= H) continue;
    const PointClass c = i < lab.cls.size() ? lab.cls[i] : PointClass::Other;
    const TColor col = c == PointClass::Ground ? TColor(175, 175, 175)
                       : c == PointClass::Obstacle ? TColor(220, 40, 40)
                       : c == PointClass::Curb ? TColor(240, 170, 0) : TColor(120, 120, 240);
    img.setPixel(u, v, col);
  }
  for (const auto& c : curb_map) img.filledRectangle(px(c.y) - 1, py(c.x) - 1, px(c.y) + 1, py(c.x) + 1, TColor(140, 80, 20));
  for (const auto& c : f.curb_points) img.drawCircle(px(c.y), py(c.x), 1, TColor(240, 170, 0), 1);
  for (const auto& o : f.obstacles) {
    const double c = std::cos(o.yaw_rad), sn = std::sin(o.yaw_rad);
    Vec2 k[4];
    for (int q = 0; q < 4; ++q) {
      const double u = (q == 0 || q == 3 ? -0.5 : 0.5) * o.length_m, v = (q < 2 ? -0.5 : 0.5) * o.width_m;
      k[q] = {o.center.x + c * u - sn * v, o.center.y + sn * u + c * v};
    }
    for (int q = 0; q < 4; ++q) img.line(px(k[q].y), py(k[q].x), px(k[(q + 1) % 4].y), py(k[(q + 1) % 4].x), TColor(150, 0, 0), 1);
  }
  const SideBoundary* sides[2] = {&f.left, &f.right};
  const TColor cols[2] = {TColor(30, 60, 230), TColor(200, 0, 200)};
  for (int k = 0; k < 2; ++k) {
    const auto& l = sides[k]->polyline_vehicle;
    for (size_t i = 1; i < l.size(); ++i) img.line(px(l[i - 1].y), py(l[i - 1].x), px(l[i].y), py(l[i].x), cols[k], 3);
  }
  img.drawCircle(px(0), py(0), 4, TColor(0, 0, 0), 2);
  img.textOut(6, 6, "frame " + std::to_string(f.index) + "  L: " + (f.left.found ? "ok" : f.left.reason), cols[0]);
  img.textOut(6, 22, "R: " + (f.right.found ? std::string("ok") : f.right.reason), cols[1]);
  const std::string tmp = tempPathFor(png_path) + ".png";
  if (!img.saveToFile(tmp)) throw std::runtime_error("cannot write " + png_path);
  commitTempFile(tmp, png_path);
}

void writeCostGridPng(const std::string& png_path, const CostGrid& g) {
  mrpt::img::CImage img(static_cast<unsigned>(std::max(g.nx, 1)), static_cast<unsigned>(std::max(g.ny, 1)),
                        mrpt::img::CH_GRAY);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i)
      img.at<uint8_t>(static_cast<unsigned>(i), static_cast<unsigned>(g.ny - 1 - j)) = g.cost[static_cast<size_t>(j) * g.nx + i];
  const std::string tmp = tempPathFor(png_path) + ".png";
  if (!img.saveToFile(tmp)) throw std::runtime_error("cannot write " + png_path);
  commitTempFile(tmp, png_path);
}

}  // namespace roadslam::boundary
