// Per-point classes: ground (libs/preprocess line fits), curbs (height step next to ground, nothing
// tall in reach), obstacles (0.3-3 m above the local ground).
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "internal.h"
#include "roadslam/boundary/detector.h"
#include "roadslam/preprocess/ground_segmentation.h"

namespace roadslam::boundary {
namespace {

struct Cell {
  float zmin = 1e9f, zmax = -1e9f;  ///< of the low points [m]
  bool ground = false, tall = false;
};

using Grid = std::unordered_map<int64_t, Cell>;

bool isLow(const preprocess::GroundLabels& gl, size_t i, const Params& p) {
  const float h = gl.height_above_ground_m[i];
  return gl.ground[i] || (std::isfinite(h) && h < p.tall_height_m);
}

Grid curbGrid(const Scan& s, const preprocess::GroundLabels& gl, const Params& p) {
  Grid g;
  g.reserve(s.points.size() / 2);
  const double r2max = p.curb_max_range_m * p.curb_max_range_m;
  for (size_t i = 0; i < s.points.size(); ++i) {
    const auto& q = s.points[i];
    if (!(q.x * q.x + q.y * q.y <= r2max)) continue;
    const float h = gl.height_above_ground_m[i];
    Cell& c = g[detail::cellKey(q.x, q.y, p.curb_cell_m)];
    if (isLow(gl, i, p)) {
      c.zmin = std::min(c.zmin, q.z), c.zmax = std::max(c.zmax, q.z);
      c.ground = c.ground || gl.ground[i];
    } else if (detail::standsTall(gl.ground[i], h, p)) {
      c.tall = true;  // its lowest ring looks like a step too
    }
  }
  return g;
}

/// The step's bottom \p zmin is the road: no low return lies more than a curb below it within
/// curb_level_cells. Otherwise the "ground" under the step is what stands on the road: a ring
/// grazing a parked car's end face descends along it at the beam's elevation slope, the ground line
/// of its sector follows it (0.3-0.7 m above the road), and face points read as a low step.
bool standsOnRoad(const Grid& g, double x, double y, float zmin, const Params& p) {
  const int k = p.curb_level_cells;
  if (k <= 0) return true;  // off; k = 0 would only compare the cell with itself
  const double c = p.curb_cell_m;
  for (int dx = -k; dx <= k; ++dx) {
    for (int dy = -k; dy <= k; ++dy) {
      auto it = g.find(detail::cellKey(x + dx * c, y + dy * c, c));
      if (it != g.end() && zmin - it->second.zmin > p.curb_max_jump_m) return false;
    }
  }
  return true;
}

/// A low point is on a curb face when its neighbourhood holds ground, spans a curb height, holds
/// nothing tall, and the point lies between the road and the top of the step.
bool onCurb(const Grid& g, double x, double y, double z, const Params& p) {
  const double c = p.curb_cell_m;
  const int k = std::max(p.curb_reach_cells, p.curb_clearance_cells);
  float zmin = 1e9f, zmax = -1e9f;
  bool ground = false;
  for (int dx = -k; dx <= k; ++dx) {
    for (int dy = -k; dy <= k; ++dy) {
      auto it = g.find(detail::cellKey(x + dx * c, y + dy * c, c));
      if (it == g.end()) continue;
      if (it->second.tall) return false;
      if (std::abs(dx) > p.curb_reach_cells || std::abs(dy) > p.curb_reach_cells) continue;
      zmin = std::min(zmin, it->second.zmin), zmax = std::max(zmax, it->second.zmax);
      ground = ground || it->second.ground;
    }
  }
  const double jump = zmax - zmin;
  // Only points on the face itself (strictly between the road and the top) mark the curb line:
  // a wide neighbourhood would otherwise smear it by its radius on both sides.
  const double margin = p.curb_face_margin * jump;
  return ground && jump >= p.curb_min_jump_m && jump <= p.curb_max_jump_m && z >= zmin + margin &&
         z <= zmax - margin && standsOnRoad(g, x, y, zmin, p);
}

}  // namespace

Labelling labelPoints(const Scan& scan, const Params& p) {
  Labelling out;
  const size_t n = scan.points.size();
  out.cls.assign(n, PointClass::Other);
  if (n == 0) return out;
  auto gl = preprocess::segmentGroundWithHeights(scan.points, p.ground);
  const Grid grid = curbGrid(scan, gl, p);
  const double roi2 = p.roi_range_m * p.roi_range_m, curb2 = p.curb_max_range_m * p.curb_max_range_m;
  const double near2 = p.curb_min_range_m * p.curb_min_range_m;
  for (size_t i = 0; i < n; ++i) {
    const auto& q = scan.points[i];
    const float h = gl.height_above_ground_m[i];
    const double r2 = q.x * q.x + q.y * q.y;
    if (r2 <= curb2 && r2 >= near2 && isLow(gl, i, p) && onCurb(grid, q.x, q.y, q.z, p)) {
      out.cls[i] = PointClass::Curb;
      ++out.curb;
    } else if (gl.ground[i]) {
      out.cls[i] = PointClass::Ground;
      ++out.ground;
    } else if (std::isfinite(h) && r2 <= roi2 && h >= p.obstacle_min_height_m && h <= p.obstacle_max_height_m) {
      out.cls[i] = PointClass::Obstacle;
      ++out.obstacle;
    }
  }
  out.height_m = std::move(gl.height_above_ground_m);
  return out;
}

}  // namespace roadslam::boundary
