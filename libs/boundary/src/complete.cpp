// A side continued parallel to the other one beyond its own curb evidence.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "internal.h"

namespace roadslam::boundary::detail {
namespace {

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/// \p line (vertices ascending in x) moved by \p w along its normal towards \p side (+1 left).
std::vector<Vec2> offsetPolyline(const std::vector<Vec2>& line, double w, int side) {
  std::vector<Vec2> out;
  for (size_t i = 0; i < line.size(); ++i) {
    const Vec2& a = line[i == 0 ? 0 : i - 1];
    const Vec2& b = line[i + 1 < line.size() ? i + 1 : i];
    const double dx = b.x - a.x, dy = b.y - a.y, n = std::hypot(dx, dy);
    if (n <= 0) continue;
    out.push_back({line[i].x - side * w * dy / n, line[i].y + side * w * dx / n});
  }
  return out;
}

}  // namespace

std::vector<Vec2> sideInliers(const std::vector<Vec2>& pts, int side, const std::vector<double>& c, const Params& p) {
  std::vector<Vec2> inl;
  for (const auto& q : pts) {
    const double lat = side * q.y;
    if (q.x < p.fit_min_x_m || q.x > p.fit_max_x_m || lat < p.min_lateral_m || lat > p.max_lateral_m) continue;
    if (std::abs(q.y - polyEval(c, q.x)) <= p.ransac_inlier_m) inl.push_back(q);
  }
  std::sort(inl.begin(), inl.end(), [](const Vec2& a, const Vec2& b) { return a.x < b.x; });
  return inl;
}

double parallelOffset(const SideBoundary& s, const SideBoundary& o, const std::vector<Vec2>& pts, int side,
                      const Params& p, double* x_end) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (p.parallel_max_spread_m <= 0 || s.coeffs.empty() || o.coeffs.empty()) return nan;
  const std::vector<Vec2> inl = sideInliers(pts, side, s.coeffs, p);
  if (static_cast<int>(inl.size()) < p.min_bins) return nan;
  // Perpendicular offsets of this side's own cells to the other side's curve (d / sqrt(1 + y'^2)).
  std::vector<double> w;
  for (const auto& q : inl) {
    const double slope = polySlope(o.coeffs, q.x);
    w.push_back(side * (q.y - polyEval(o.coeffs, q.x)) / std::sqrt(1 + slope * slope));
  }
  const double wm = median(w);
  for (double& v : w) v = std::abs(v - wm);
  if (median(w) > p.parallel_max_spread_m || wm < 2 * p.min_lateral_m) return nan;
  if (x_end) *x_end = inl.back().x;
  return wm;
}

bool completeParallel(SideBoundary& s, const SideBoundary& o, const std::vector<Vec2>& pts, int side,
                      const Params& p, double road_width_m) {
  if (!o.found || o.polyline_vehicle.size() < 2 || !std::isfinite(road_width_m)) return false;
  double x_end = 0;  // own evidence ends here
  const double wm = parallelOffset(s, o, pts, side, p, &x_end);
  // The offset must be the road's width as measured where both curbs were seen: cells along a row
  // of parked cars' sills lie parallel to the far curb too, at the wrong offset.
  if (!std::isfinite(wm) || std::abs(wm - road_width_m) > p.parallel_width_gate_m) return false;
  const std::vector<Vec2> inl = sideInliers(pts, side, s.coeffs, p);
  std::vector<Vec2> own;
  for (const auto& v : s.polyline_vehicle)
    if (s.found && v.x <= x_end + p.bin_m) own.push_back(v);
  std::vector<Vec2> line;
  for (const auto& v : offsetPolyline(o.polyline_vehicle, wm, side)) {
    if (v.x > p.band_max_x_m) break;
    if (!own.empty() && v.x > own.front().x - 0.5 * p.polyline_step_m) {
      if (v.x <= own.back().x + 0.5 * p.polyline_step_m) continue;
      if (line.empty() || line.back().x < own.front().x) line.insert(line.end(), own.begin(), own.end());
    }
    line.push_back(v);
  }
  if (!own.empty() && (line.empty() || line.back().x < own.front().x)) line.insert(line.end(), own.begin(), own.end());
  if (line.size() < 2 || line.size() == own.size()) return false;
  if (!s.found) {
    std::ostringstream why;
    why << std::fixed;
    why.precision(2);
    why << "continued parallel to the " << (side > 0 ? "right" : "left") << " curb at " << wm
        << " m (the road's width) beyond its own curb cells (up to x = " << x_end << " m)";
    s.reason = why.str();
    s.confidence = 0.5 * o.confidence;
  }
  s.found = true;
  s.parallel_m = static_cast<double>(line.size() - own.size()) * p.polyline_step_m;
  int bridged = 0;
  for (const auto& v : line) {
    const auto it = std::lower_bound(inl.begin(), inl.end(), v.x - p.bin_m, [](const Vec2& q, double x) { return q.x < x; });
    bridged += !(it != inl.end() && it->x <= v.x + p.bin_m && std::abs(it->y - v.y) < 1.0);
  }
  s.bridged_m = bridged * p.polyline_step_m;
  s.confidence *= 1.0 - 0.5 * bridged / static_cast<double>(line.size());
  s.polyline_vehicle = std::move(line);
  return true;
}

}  // namespace roadslam::boundary::detail
