#pragma once
// Private helpers of libs/boundary.
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "roadslam/boundary/params.h"
#include "roadslam/boundary/types.h"

namespace roadslam::boundary::detail {

inline int64_t cellKey(double x, double y, double cell) {
  const auto ix = static_cast<int64_t>(std::floor(x / cell)), iy = static_cast<int64_t>(std::floor(y / cell));
  return (ix << 32) ^ (iy & 0xffffffffLL);
}

/// Coordinates along the arc the vehicle is driving (curvature \p kappa [1/m], from the origin along
/// +x): s = arc length [m], d = offset to the left of the arc [m]. A curb concentric with the
/// vehicle's path through a corner is d = const, so the side fits (polynomials in s) follow corners
/// while the vehicle turns; kappa = 0 is the vehicle frame itself.
struct ArcFrame {
  double kappa = 0;
  static constexpr double kMaxAngle = 2.0;  ///< farther round the arc than this the map is ambiguous [rad]
  bool straight() const { return std::abs(kappa) < 1e-4; }
  /// (x, y) -> (s, d); false beyond kMaxAngle or across the centre of curvature.
  bool toArc(const Vec2& q, Vec2& out) const {
    if (straight()) return out = q, true;
    const double R = 1.0 / kappa, sg = R > 0 ? 1.0 : -1.0;
    const double rho = sg * std::hypot(q.x, R - q.y);  // R - d
    const double th = std::atan2(q.x / rho, (R - q.y) / rho);
    if (std::abs(th) > kMaxAngle) return false;
    out = {th * R, R - rho};
    return true;
  }
  Vec2 toXY(const Vec2& a) const {
    if (straight()) return a;
    const double R = 1.0 / kappa, th = a.x * kappa;
    return {(R - a.y) * std::sin(th), R - (R - a.y) * std::cos(th)};
  }
};

/// Convex hull, counter-clockwise (Andrew's monotone chain).
std::vector<Vec2> convexHull(std::vector<Vec2> pts);
/// Minimum-area rectangle of a convex hull (one side on a hull edge: Freeman & Shapira 1975).
void orientedRect(const std::vector<Vec2>& hull, Obstacle& o);
/// Clusters \p pts on a grid of cell \p cell (8-connected cells = Euclidean clustering at ~cell).
std::vector<std::vector<size_t>> gridClusters(const std::vector<Vec2>& pts, double cell);

/// RANSAC polynomial fit of one side (side = +1 left, -1 right) over curb points, vehicle frame.
SideBoundary fitSide(const std::vector<Vec2>& pts, int side, const Params& p, std::mt19937& rng);
/// Curb points of one side within ransac_inlier_m of the polynomial \p c, ascending in x.
std::vector<Vec2> sideInliers(const std::vector<Vec2>& pts, int side, const std::vector<double>& c, const Params& p);
/// Median perpendicular offset [m] of the curb cells of side \p s (side = +1 left, -1 right; a fit,
/// found or not) from the curve of the other side \p o; NaN when fewer than min_bins cells or when
/// their offsets spread (median absolute deviation) more than parallel_max_spread_m. \p x_end gets
/// the largest x of those cells [m].
double parallelOffset(const SideBoundary& s, const SideBoundary& o, const std::vector<Vec2>& pts, int side,
                      const Params& p, double* x_end = nullptr);
/// Continues side \p s beyond (and before) its own curb cells parallel to the found side \p o, at
/// their offset when it matches \p road_width_m (measured where both sides were seen) within
/// parallel_width_gate_m. Returns whether \p s changed; a side found only this way says so.
bool completeParallel(SideBoundary& s, const SideBoundary& o, const std::vector<Vec2>& pts, int side, const Params& p,
                      double road_width_m);
/// Thesis baseline: inner corners of the rectangles of non-ground clusters, RANSAC line.
SideBoundary fitSideThesis(const std::vector<Obstacle>& rects, int side, const Params& p, std::mt19937& rng);

/// y of the polynomial \p c at \p x.
inline double polyEval(const std::vector<double>& c, double x) {
  double y = 0, xp = 1;
  for (double ci : c) {
    y += ci * xp;
    xp *= x;
  }
  return y;
}

}  // namespace roadslam::boundary::detail
