#include <cerrno>
#include <mrpt/img/CImage.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/sim/outputs.h"

namespace roadslam::sim {

namespace {
using mrpt::img::TColor;

constexpr int kBand = 30;  // [px] text band above and scale band below the map

struct View {
  double x0, y0, scale;
  int w, h;  ///< whole image [px]
  int px(double x) const { return static_cast<int>(std::lround((x - x0) * scale)); }
  int py(double y) const { return h - 1 - kBand - static_cast<int>(std::lround((y - y0) * scale)); }
};

TColor colorOf(Material m) {
  switch (m) {
    case Material::Concrete: return {205, 205, 200};
    case Material::Facade: return {170, 120, 90};
    case Material::Glass: return {90, 150, 210};
    case Material::CarPaint: return {70, 90, 200};
    case Material::DarkPaint: return {40, 40, 50};
    case Material::Metal: return {0, 0, 0};
    case Material::TunnelWall: return {110, 110, 110};
    default: return {150, 150, 150};
  }
}

void fillPrism(mrpt::img::CImage& img, const View& v, const Prism& p, TColor col) {
  const double c = std::cos(p.yaw), s = std::sin(p.yaw);
  const double step = 0.5 / v.scale;  // half a pixel
  for (double b = -p.hv; b <= p.hv + 1e-9; b += step) {
    const double x0 = p.cx - p.hu * c - b * s, y0 = p.cy - p.hu * s + b * c;
    const double x1 = p.cx + p.hu * c - b * s, y1 = p.cy + p.hu * s + b * c;
    img.line(v.px(x0), v.py(y0), v.px(x1), v.py(y1), col);
  }
}

void polyline(mrpt::img::CImage& img, const View& v, const std::vector<Vec2>& l, bool closed, TColor col,
              unsigned width) {
  for (std::size_t i = 1; i < l.size() + (closed ? 1 : 0); ++i) {
    const Vec2& a = l[i - 1];
    const Vec2& b = l[i % l.size()];
    img.line(v.px(a.x), v.py(a.y), v.px(b.x), v.py(b.y), col, width);
  }
}
}  // namespace

void drawTopView(const Simulator& sim, const std::string& png_path, int max_px) {
  const World& w = sim.world();
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  for (const Road& r : w.roads)
    for (const Vec2& q : r.centerline) {
      xmin = std::min(xmin, q.x); ymin = std::min(ymin, q.y);
      xmax = std::max(xmax, q.x); ymax = std::max(ymax, q.y);
    }
  const double margin = 40;
  xmin -= margin; ymin -= margin; xmax += margin; ymax += margin;
  const double scale = max_px / std::max(xmax - xmin, ymax - ymin);
  View v{xmin, ymin, scale, static_cast<int>((xmax - xmin) * scale) + 1,
         static_cast<int>((ymax - ymin) * scale) + 1 + 2 * kBand};
  mrpt::img::CImage img(static_cast<unsigned>(v.w), static_cast<unsigned>(v.h), mrpt::img::CH_RGB);
  img.filledRectangle(0, 0, v.w - 1, v.h - 1, TColor(236, 236, 222));
  if (w.ground.amplitude_m > 0) {  // terrain height: darker is lower, in 6 px blocks
    const double A = 1.5 * w.ground.amplitude_m;
    for (int y = 0; y < v.h; y += 6)
      for (int x = 0; x < v.w; x += 6) {
        const double f = std::clamp(0.5 + 0.5 * w.ground.height(v.x0 + (x + 3) / v.scale,
                                                                v.y0 + (v.h - 1 - kBand - y - 3) / v.scale) / A, 0.0, 1.0);
        const auto c = static_cast<uint8_t>(170 + 80 * f);
        img.filledRectangle(x, y, x + 5, y + 5, TColor(c, c, static_cast<uint8_t>(c - 20)));
      }
  }
  for (const Road& r : w.roads)
    polyline(img, v, r.centerline, r.closed, TColor(95, 95, 95),
             static_cast<unsigned>(std::max(1.0, 2 * r.half_width_m * scale)));
  for (int pass = 0; pass < 2; ++pass)  // sidewalks first, everything else on top
    for (const Prism& p : w.prisms) {
      if ((p.material == Material::Concrete) != (pass == 0)) continue;
      if (p.material == Material::TunnelWall && p.hv > 1.0) continue;  // ceilings: keep the road visible
      fillPrism(img, v, p, colorOf(p.material));
    }
  for (const Sphere& s : w.spheres)
    img.drawCircle(v.px(s.c.x), v.py(s.c.y), std::max(1, static_cast<int>(s.r * scale)), TColor(30, 140, 40), 1);
  for (const Cylinder& c : w.cylinders)
    img.drawCircle(v.px(c.cx), v.py(c.cy), 1, colorOf(c.material), 1);
  for (const Road& r : w.roads) {
    for (const auto& c : r.left_curbs) polyline(img, v, c, false, TColor(0, 170, 0), 1);
    for (const auto& c : r.right_curbs) polyline(img, v, c, false, TColor(0, 170, 0), 1);
  }
  for (const MovingCar& c : w.cars) fillPrism(img, v, w.carPrism(c, 0), TColor(220, 0, 220));
  // The whole planned drive thin, the simulated part (up to duration_s) thick.
  std::vector<Vec2> planned, simulated;
  for (const VehicleState& s : sim.trajectory().states()) {
    planned.push_back({s.x, s.y});
    if (s.t_s <= sim.duration_s()) simulated.push_back({s.x, s.y});
  }
  polyline(img, v, planned, false, TColor(240, 120, 120), 1);
  polyline(img, v, simulated, false, TColor(230, 0, 0), 3);
  if (!planned.empty()) img.drawCircle(v.px(planned.front().x), v.py(planned.front().y), 8, TColor(0, 0, 255), 2);
  const int bar = static_cast<int>(100 * scale);
  img.line(10, v.h - 15, 10 + bar, v.h - 15, TColor(0, 0, 0), 3);
  img.textOut(12, v.h - 32, "100 m", TColor(0, 0, 0));
  img.textOut(10, 8, sim.params().name + "  seed " + std::to_string(sim.params().seed) +
                         "  red: drive (thick: simulated), green: curbs, blue circle: start, magenta: moving cars at t=0", TColor(0, 0, 0));
  TempFile tmp(png_path, ".png");  // the extension selects the format
  errno = 0;
  if (!img.saveToFile(tmp.path())) throw std::runtime_error(tmp.failure());
  tmp.commit();
}

}  // namespace roadslam::sim
