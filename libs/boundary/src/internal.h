#pragma once
// Private helpers of libs/boundary.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "roadslam/boundary/params.h"
#include "roadslam/boundary/types.h"

namespace roadslam::boundary::detail {

/// Cell (ix, iy) packed into one key: ix in the high 32 bits, iy in the low. Shifted as unsigned (a
/// negative ix shifted left is undefined in C++17; UBSan found it); the bits are two's complement.
inline int64_t packCell(int64_t ix, int64_t iy) {
  return static_cast<int64_t>((static_cast<uint64_t>(ix) << 32) ^ (static_cast<uint64_t>(iy) & 0xffffffffULL));
}

inline int64_t cellKey(double x, double y, double cell) {
  return packCell(static_cast<int64_t>(std::floor(x / cell)), static_cast<int64_t>(std::floor(y / cell)));
}

/// Something standing (a car side, wall or trunk) rather than road or curb: off the ground, between
/// tall_height_m and tall_max_height_m above it (tree crowns above pass). No curb may neighbour it.
inline bool standsTall(bool ground, float height_m, const Params& p) {
  return !ground && height_m >= p.tall_height_m && height_m <= p.tall_max_height_m;
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

/// Coordinates along the drive's own path (whole-drive mode, where the whole trajectory is known):
/// s = arc length along the path [m] (0 at the vehicle), d = offset to its left [m]. The path is a
/// polyline of the vehicle's positions, vehicle frame; past its first and last vertex it goes on
/// straight. A curb along the road the vehicle drives is d = const through any
/// corner, where one arc (ArcFrame, BendFrame) only holds for one piece of it.
///
/// Offsets are taken along normals interpolated between the vertices' (each vertex's is the bisector
/// of its segments'), not to the nearest point: on the inner side of a turn the nearest point of a
/// polyline jumps ahead by d tan(a/2) at each vertex turning by a (0.2 m for a curb 4 m inside a
/// 14 m radius sampled every 1.5 m), on the outer side it stalls.
struct PathFrame {
  std::vector<Vec2> v;    ///< vertices, vehicle frame [m]
  std::vector<double> s;  ///< arc length at each vertex [m]
  std::vector<Vec2> n;    ///< unit normal (left) at each vertex [-]
  /// (x, y) -> (s, d): the point of the path whose (interpolated) normal passes through (x, y), the
  /// nearest of them; false when there is none (a path of fewer than 2 vertices).
  bool toArc(const Vec2& q, Vec2& out) const;
  Vec2 toXY(const Vec2& a) const;
};

/// The path of the drive \p positions_map (vehicle positions in the map frame, in driving order)
/// around its vertex \p k, in the vehicle frame at \p T_map_lidar: from \p behind_m behind to
/// \p ahead_m ahead (arc length), one vertex per \p step_m, s = 0 at the vehicle.
PathFrame pathAround(const std::vector<Eigen::Vector3d>& positions_map, size_t k, const Eigen::Isometry3d& T_map_lidar,
                     double behind_m, double ahead_m, double step_m);

/// The driven path's arc (curvature a.kappa from the origin along +x) up to arc length s_bend, then an
/// arc of curvature b.kappa tangent to it: the road ahead of a corner entry (straight, then the bend)
/// or exit (the bend, then straight). Curbs concentric with both pieces are d = const: circles about
/// the second piece's centre touch their tangent lines at s = s_bend. s_bend = inf is ArcFrame a.
struct BendFrame {
  ArcFrame a;                                              ///< from the vehicle [1/m]
  double s_bend = std::numeric_limits<double>::infinity(); ///< arc length where b takes over [m]
  ArcFrame b;                                              ///< beyond s_bend [1/m]
  const PathFrame* path = nullptr;  ///< set: the frame is this path's (whole-drive mode), a and b unused
  bool bent() const { return std::isfinite(s_bend); }
  /// Pose (position, heading) of the path at s_bend, vehicle frame.
  Vec2 bendPoint() const { return a.toXY({s_bend, 0.0}); }
  double bendHeading() const { return a.kappa * s_bend; }
  bool toArc(const Vec2& q, Vec2& out) const {
    if (path) return path->toArc(q, out);
    Vec2 o;
    if (a.toArc(q, o) && o.x <= s_bend) return out = o, true;
    if (!bent()) return false;
    const Vec2 P = bendPoint();
    const double c = std::cos(bendHeading()), s = std::sin(bendHeading());
    const double dx = q.x - P.x, dy = q.y - P.y;
    if (!b.toArc({c * dx + s * dy, -s * dx + c * dy}, o) || o.x < 0) return false;
    out = {s_bend + o.x, o.y};
    return true;
  }
  Vec2 toXY(const Vec2& q) const {
    if (path) return path->toXY(q);
    if (q.x <= s_bend) return a.toXY(q);
    const Vec2 P = bendPoint(), l = b.toXY({q.x - s_bend, q.y});
    const double c = std::cos(bendHeading()), s = std::sin(bendHeading());
    return {P.x + c * l.x - s * l.y, P.y + s * l.x + c * l.y};
  }
};

/// The frame to fit the sides in: the driven path's arc (\p kappa_path), unless a frame bent ahead
/// (BendFrame over a grid of s_bend and curvatures) lines up bend_margin_bins more 1 m bins of the
/// curb cells \p cells (vehicle frame) at constant offsets on the two sides (a Hough vote: the bend is
/// in the curb map before the vehicle turns). \p votes gets the chosen and the path frame's votes.
BendFrame chooseFrame(const std::vector<Vec2>& cells, double kappa_path, const Params& p, int votes[2] = nullptr);

/// Convex hull, counter-clockwise (Andrew's monotone chain).
std::vector<Vec2> convexHull(std::vector<Vec2> pts);

/// RANSAC polynomial fit of one side (side = +1 left, -1 right) over curb points, vehicle frame.
SideBoundary fitSide(const std::vector<Vec2>& pts, int side, const Params& p, std::mt19937& rng);

/// y of the polyline \p line (vertices ascending in x) at \p x, NaN outside it.
double yAt(const std::vector<Vec2>& line, double x);
/// Mean |y_line - y_held| over the held points in the band ahead (\p n of them); 0 when none.
double deviationInBand(const std::vector<Vec2>& line, const std::vector<Vec2>& held, const Params& p, int* n);
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

/// dy/dx of the polynomial \p c (degree <= 2, as fitted) at \p x.
inline double polySlope(const std::vector<double>& c, double x) {
  return c.size() > 1 ? c[1] + (c.size() > 2 ? 2 * c[2] * x : 0.0) : 0.0;
}

}  // namespace roadslam::boundary::detail
