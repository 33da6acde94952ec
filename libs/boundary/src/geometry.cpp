// Clustering and shape helpers: grid clustering, convex hull, minimum-area rectangle.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "internal.h"

namespace roadslam::boundary::detail {

std::vector<Vec2> convexHull(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (pts.size() < 3) return pts;
  auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<Vec2> h(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  return h;
}

void orientedRect(const std::vector<Vec2>& hull, Obstacle& o) {
  double best = 1e300;
  const size_t n = hull.size();
  for (size_t e = 0; e < std::max<size_t>(n, 1); ++e) {
    double th = 0;
    if (n >= 2) th = std::atan2(hull[(e + 1) % n].y - hull[e].y, hull[(e + 1) % n].x - hull[e].x);
    const double c = std::cos(th), s = std::sin(th);
    double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
    for (const auto& q : hull) {
      const double u = c * q.x + s * q.y, v = -s * q.x + c * q.y;
      u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
    }
    if (n == 0) u0 = u1 = v0 = v1 = 0;
    const double area = (u1 - u0) * (v1 - v0);
    if (area >= best) continue;
    best = area;
    const double uc = 0.5 * (u0 + u1), vc = 0.5 * (v0 + v1);
    o.center = {c * uc - s * vc, s * uc + c * vc};
    const bool u_long = (u1 - u0) >= (v1 - v0);
    o.length_m = u_long ? u1 - u0 : v1 - v0;
    o.width_m = u_long ? v1 - v0 : u1 - u0;
    o.yaw_rad = u_long ? th : th + M_PI / 2;
  }
  o.yaw_rad = std::remainder(o.yaw_rad, M_PI);  // a rectangle's direction is defined modulo pi
}

std::vector<std::vector<size_t>> gridClusters(const std::vector<Vec2>& pts, double cell) {
  std::unordered_map<int64_t, std::vector<size_t>> cells;
  for (size_t i = 0; i < pts.size(); ++i) cells[cellKey(pts[i].x, pts[i].y, cell)].push_back(i);
  std::unordered_map<int64_t, int> label;
  std::vector<std::vector<size_t>> out;
  std::vector<int64_t> stack;
  for (const auto& [key, idx] : cells) {
    if (label.count(key)) continue;
    const int id = static_cast<int>(out.size());
    out.emplace_back();
    label[key] = id;
    stack.assign(1, key);
    while (!stack.empty()) {
      const int64_t k = stack.back();
      stack.pop_back();
      const auto& members = cells[k];
      out[id].insert(out[id].end(), members.begin(), members.end());
      const int64_t ix = k >> 32, iy = static_cast<int32_t>(k & 0xffffffffLL);
      for (int dx = -1; dx <= 1; ++dx) {
        for (int dy = -1; dy <= 1; ++dy) {
          const int64_t nk = packCell(ix + dx, iy + dy);
          if (cells.count(nk) && !label.count(nk)) {
            label[nk] = id;
            stack.push_back(nk);
          }
        }
      }
    }
  }
  return out;
}

}  // namespace roadslam::boundary::detail
