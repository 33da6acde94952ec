// The fit frame of the whole-drive mode: arc length and offset along the drive's own path.
#include <algorithm>
#include <cmath>
#include <limits>

#include "internal.h"

namespace roadslam::boundary::detail {

namespace {
double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }
}  // namespace

// On segment i, a point p(t) = v_i + t (v_i+1 - v_i) with normal n(t) = (1 - t) n_i + t n_i+1 (not
// unit) reaches q when q - p(t) is parallel to n(t): cross(q - p(t), n(t)) = 0, quadratic in t.
bool PathFrame::toArc(const Vec2& q, Vec2& out) const {
  double best = std::numeric_limits<double>::infinity();
  const size_t m = v.size();
  for (size_t i = 0; i + 1 < m; ++i) {
    const double ux = v[i + 1].x - v[i].x, uy = v[i + 1].y - v[i].y, L = s[i + 1] - s[i];
    if (!(L > 0)) continue;
    const double wx = q.x - v[i].x, wy = q.y - v[i].y;
    const double dnx = n[i + 1].x - n[i].x, dny = n[i + 1].y - n[i].y;
    const double A = -cross(ux, uy, dnx, dny), B = cross(wx, wy, dnx, dny) - cross(ux, uy, n[i].x, n[i].y),
                 C = cross(wx, wy, n[i].x, n[i].y);
    double roots[2];
    int nr = 0;
    if (std::abs(A) < 1e-12) {
      if (std::abs(B) > 1e-12) roots[nr++] = -C / B;
    } else {
      const double disc = B * B - 4 * A * C;
      if (disc >= 0) {
        const double r = std::sqrt(disc), qq = -0.5 * (B + (B >= 0 ? r : -r));  // stable pair of roots
        roots[nr++] = qq / A;
        if (qq != 0) roots[nr++] = C / qq;
      }
    }
    for (int k = 0; k < nr; ++k) {
      const double t = roots[k];
      // The first and last segments go on straight (their normals are the segments').
      if ((i > 0 && t < -1e-9) || (i + 2 < m && t > 1 + 1e-9)) continue;
      const double nx = n[i].x + t * dnx, ny = n[i].y + t * dny, nn = std::hypot(nx, ny);
      if (!(nn > 1e-9)) continue;
      const double d = ((wx - t * ux) * nx + (wy - t * uy) * ny) / nn;
      if (std::abs(d) < best) best = std::abs(d), out = {s[i] + t * L, d};
    }
  }
  return std::isfinite(best);
}

Vec2 PathFrame::toXY(const Vec2& a) const {
  size_t i = 0;
  while (i + 2 < v.size() && s[i + 1] < a.x) ++i;
  const double t = (a.x - s[i]) / (s[i + 1] - s[i]);
  const double nx = n[i].x + t * (n[i + 1].x - n[i].x), ny = n[i].y + t * (n[i + 1].y - n[i].y), nn = std::hypot(nx, ny);
  return {v[i].x + t * (v[i + 1].x - v[i].x) + a.y * nx / nn, v[i].y + t * (v[i + 1].y - v[i].y) + a.y * ny / nn};
}

PathFrame pathAround(const std::vector<Eigen::Vector3d>& positions_map, size_t k, const Eigen::Isometry3d& T_map_lidar,
                     double behind_m, double ahead_m, double step_m) {
  const Eigen::Isometry3d T_lidar_map = T_map_lidar.inverse();
  auto walk = [&](int dir, double reach) {  // vertices >= step_m apart from the vehicle on, one way
    std::vector<Vec2> out;
    Vec2 last{0, 0};
    double len = 0;
    for (long i = static_cast<long>(k) + dir; i >= 0 && i < static_cast<long>(positions_map.size()) && len < reach; i += dir) {
      const Eigen::Vector3d p = T_lidar_map * positions_map[static_cast<size_t>(i)];
      const double d = std::hypot(p.x() - last.x, p.y() - last.y);
      if (d < step_m) continue;
      len += d, last = {p.x(), p.y()};
      out.push_back(last);
    }
    if (out.empty()) out.push_back({dir * step_m, 0.0});  // an end of the drive: straight on
    return out;
  };
  const std::vector<Vec2> back = walk(-1, behind_m), ahead = walk(+1, ahead_m);
  PathFrame f;
  f.v.assign(back.rbegin(), back.rend());
  f.v.push_back({0, 0});
  const size_t i0 = f.v.size() - 1;
  f.v.insert(f.v.end(), ahead.begin(), ahead.end());
  f.s.assign(f.v.size(), 0.0);
  for (size_t i = 1; i < f.v.size(); ++i) f.s[i] = f.s[i - 1] + std::hypot(f.v[i].x - f.v[i - 1].x, f.v[i].y - f.v[i - 1].y);
  const double s0 = f.s[i0];
  for (double& x : f.s) x -= s0;
  const size_t m = f.v.size();
  std::vector<Vec2> seg(m - 1);  // unit left normals of the segments
  for (size_t i = 0; i + 1 < m; ++i) {
    const double L = std::max(f.s[i + 1] - f.s[i], 1e-9);
    seg[i] = {-(f.v[i + 1].y - f.v[i].y) / L, (f.v[i + 1].x - f.v[i].x) / L};
  }
  f.n.resize(m);
  for (size_t i = 0; i < m; ++i) {
    const Vec2 a = seg[i == 0 ? 0 : i - 1], b = seg[i + 1 < m ? i : m - 2];
    const double nx = a.x + b.x, ny = a.y + b.y, nn = std::hypot(nx, ny);
    f.n[i] = nn > 1e-9 ? Vec2{nx / nn, ny / nn} : b;  // a U-turn in one vertex: the next segment's
  }
  return f;
}

}  // namespace roadslam::boundary::detail
