#include "roadslam/objects/segmentation.h"

#include <Eigen/Cholesky>

#include "range_image.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace roadslam::objects {
namespace {

constexpr double kClosenessFloor_m = 0.01;  // d0 of Zhang et al. 2017, Alg. 4 (avoids 1/0)
constexpr size_t kMaxFitPoints = 256;       // the L-shape search sees at most this many points (stride)
constexpr int kCoarseSteps = 5;             // coarse L-shape search step, in fine steps

/// Labels of connected components over the candidate points; -1 = not a candidate.
using Labels = std::vector<int>;

/// Connected components of the candidates under "within \p dist_m in x-y": from each unlabelled
/// point, a flood over the points \p forNeighbours(i, visit) offers (each index to visit(j)).
/// Returns the number of components.
template <class ForNeighbours>
int floodComponents(const std::vector<ScanPoint>& pts, const std::vector<uint32_t>& cand, double dist_m, Labels& label,
                    ForNeighbours&& forNeighbours) {
  const double d2 = dist_m * dist_m;
  int n = 0;
  std::vector<uint32_t> stack;
  for (uint32_t i0 : cand) {
    if (label[i0] >= 0) continue;
    label[i0] = n;
    stack.assign(1, i0);
    while (!stack.empty()) {
      const uint32_t i = stack.back();
      stack.pop_back();
      const ScanPoint& q = pts[i];
      forNeighbours(i, [&](uint32_t j) {
        if (label[j] >= 0) return;
        const double dx = pts[j].x - q.x, dy = pts[j].y - q.y;
        if (dx * dx + dy * dy > d2) return;
        label[j] = n;
        stack.push_back(j);
      });
    }
    ++n;
  }
  return n;
}

/// Range image: each candidate point goes to its (ring, azimuth) cell (a cell may hold several: a
/// chain). Components grow from a point to the points of the cells within ring_window x
/// azimuth_window around its own that are within cluster_distance_m in x-y.
int rangeImageComponents(const std::vector<ScanPoint>& pts, const std::vector<uint32_t>& cand, const ClusterParams& p,
                         Labels& label) {
  int rings = 0;
  for (uint32_t i : cand) rings = std::max(rings, static_cast<int>(pts[i].ring) + 1);
  const int bins = p.azimuth_bins;
  std::vector<int> head(static_cast<size_t>(rings) * bins, -1);  // first point of each cell
  std::vector<int> next(pts.size(), -1), cell_of(pts.size(), -1);
  for (uint32_t i : cand) {
    const int a = detail::azimuthColumn(pts[i].x, pts[i].y, bins);
    const int c = pts[i].ring * bins + a;
    cell_of[i] = c;
    next[i] = head[static_cast<size_t>(c)];
    head[static_cast<size_t>(c)] = static_cast<int>(i);
  }
  return floodComponents(pts, cand, p.cluster_distance_m, label, [&](uint32_t i, auto&& visit) {
    const int r = cell_of[i] / bins, a = cell_of[i] % bins;
    for (int rr = std::max(0, r - p.ring_window); rr <= std::min(rings - 1, r + p.ring_window); ++rr) {
      for (int da = -p.azimuth_window; da <= p.azimuth_window; ++da) {
        const int aa = (a + da + bins) % bins;
        for (int j = head[static_cast<size_t>(rr) * bins + aa]; j >= 0; j = next[static_cast<size_t>(j)]) {
          visit(static_cast<uint32_t>(j));
        }
      }
    }
  });
}

/// The candidates on an x-y grid of \p cell metres: forCell(i, visit) offers every point of the 3 x 3
/// cells around point i, which hold every point within \p cell of it.
class XyGrid {
 public:
  XyGrid(const std::vector<ScanPoint>& pts, const std::vector<uint32_t>& cand, double cell) : pts_(pts), cell_(cell) {
    grid_.reserve(cand.size());
    for (uint32_t i : cand) grid_[key(cellOf(pts[i].x), cellOf(pts[i].y))].push_back(i);
  }
  template <class Visit>
  void forNeighbours(uint32_t i, Visit&& visit) const {
    // integer cells: offsets of the coordinate (x +- cell) can round into one cell twice or skip one
    const int64_t ix = cellOf(pts_[i].x), iy = cellOf(pts_[i].y);
    for (int64_t dx = -1; dx <= 1; ++dx) {
      for (int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = grid_.find(key(ix + dx, iy + dy));
        if (it == grid_.end()) continue;
        for (uint32_t j : it->second) visit(j);
      }
    }
  }

 private:
  int64_t cellOf(double v) const { return static_cast<int64_t>(std::floor(v / cell_)); }
  // unsigned: a negative cell shifted left is undefined behaviour (UBSan); the same bits
  static int64_t key(int64_t ix, int64_t iy) {
    return static_cast<int64_t>((static_cast<uint64_t>(ix) << 32) ^ (static_cast<uint64_t>(iy) & 0xffffffffu));
  }
  const std::vector<ScanPoint>& pts_;
  double cell_;
  std::unordered_map<int64_t, std::vector<uint32_t>> grid_;
};

/// Euclidean clusters: components of points within cluster_distance_m of each other.
int euclideanComponents(const std::vector<ScanPoint>& pts, const std::vector<uint32_t>& cand, const ClusterParams& p,
                        Labels& label) {
  const XyGrid grid(pts, cand, p.cluster_distance_m);
  return floodComponents(pts, cand, p.cluster_distance_m, label,
                         [&](uint32_t i, auto&& visit) { grid.forNeighbours(i, visit); });
}

/// DBSCAN (Ester et al., KDD 1996) in x-y with eps = cluster_distance_m, MinPts = dbscan_min_points:
/// clusters grow through core points (>= MinPts points within eps, itself included); a non-core point
/// within eps of a core joins its cluster (border) without growing it; the rest is noise (label -1).
int dbscanComponents(const std::vector<ScanPoint>& pts, const std::vector<uint32_t>& cand, const ClusterParams& p,
                     Labels& label) {
  const double eps2 = p.cluster_distance_m * p.cluster_distance_m;
  const XyGrid grid(pts, cand, p.cluster_distance_m);
  std::vector<char> core(pts.size(), 0);
  for (uint32_t i : cand) {
    int n = 0;
    grid.forNeighbours(i, [&](uint32_t j) {
      const double dx = pts[j].x - pts[i].x, dy = pts[j].y - pts[i].y;
      n += dx * dx + dy * dy <= eps2;
    });
    core[i] = n >= p.dbscan_min_points;
  }
  std::vector<uint32_t> cores;
  for (uint32_t i : cand) {
    if (core[i]) cores.push_back(i);
  }
  // components of the core points, then each border point to the cluster of a core within eps
  const int n = floodComponents(pts, cores, p.cluster_distance_m, label, [&](uint32_t i, auto&& visit) {
    grid.forNeighbours(i, [&](uint32_t j) {
      if (core[j]) visit(j);
    });
  });
  for (uint32_t i : cand) {
    if (core[i]) continue;
    grid.forNeighbours(i, [&](uint32_t j) {
      if (label[i] >= 0 || !core[j]) return;
      const double dx = pts[j].x - pts[i].x, dy = pts[j].y - pts[i].y;
      if (dx * dx + dy * dy <= eps2) label[i] = label[j];
    });
  }
  return n;
}

/// The road around the sensor as a plane z = a x + b y + c, for the points no ground line reaches (a
/// far car's sector, whose road the car itself shadows): their height above it instead of above a
/// level road at -sensor_height_m. A car rolls out of a turn by 3-7 deg/g and pitches by 1-2 deg/g
/// (Gillespie 1992, ch. 7-8), 1.25 deg in a 2.5 m/s^2 turn, which is 0.55 m at 25 m to the side. Least
/// squares over the ground points within kPlaneRange_m (already labelled: no RANSAC hypothesis search,
/// preprocess::fitGroundPlaneRansac's job on unlabelled points), refit once without those farther than
/// kPlaneResidual_m; level where they are too few or the fit tilts more than kPlaneMaxTilt.
struct GroundPlane {
  double a = 0, b = 0, c = 0;
  double at(double x, double y) const { return a * x + b * y + c; }
};

constexpr double kPlaneRange_m = 25.0;
constexpr double kPlaneResidual_m = 0.15;
constexpr double kPlaneMaxTilt = 0.1;  // |grad z|: 5.7 deg
constexpr size_t kPlaneMinPoints = 50;

GroundPlane fitGroundPlane(const std::vector<ScanPoint>& pts, const std::vector<uint8_t>& ground, double sensor_height_m) {
  const GroundPlane level{0, 0, -sensor_height_m};
  std::vector<uint32_t> idx;
  for (size_t i = 0; i < std::min(pts.size(), ground.size()); ++i) {
    const ScanPoint& q = pts[i];
    if (ground[i] && std::isfinite(q.z) && double(q.x) * q.x + double(q.y) * q.y < kPlaneRange_m * kPlaneRange_m)
      idx.push_back(static_cast<uint32_t>(i));
  }
  GroundPlane g = level;
  for (int pass = 0; pass < 2; ++pass) {
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    size_t n = 0;
    for (uint32_t i : idx) {
      const ScanPoint& q = pts[i];
      if (pass > 0 && std::abs(q.z - g.at(q.x, q.y)) > kPlaneResidual_m) continue;
      const Eigen::Vector3d r(q.x, q.y, 1.0);
      A += r * r.transpose(), rhs += r * double(q.z), ++n;
    }
    if (n < kPlaneMinPoints) return level;
    const Eigen::Vector3d x = A.ldlt().solve(rhs);
    if (!x.allFinite() || std::hypot(x(0), x(1)) > kPlaneMaxTilt) return level;
    g = {x(0), x(1), x(2)};
  }
  return g;
}

}  // namespace

size_t fillUnknownHeights(const std::vector<ScanPoint>& pts, const std::vector<uint8_t>& ground, double sensor_height_m,
                          std::vector<float>& heights) {
  const GroundPlane plane = fitGroundPlane(pts, ground, sensor_height_m);
  size_t n = 0;
  for (size_t i = 0; i < std::min(pts.size(), heights.size()); ++i) {
    if (std::isfinite(heights[i])) continue;
    const ScanPoint& q = pts[i];
    heights[i] = static_cast<float>(q.z - plane.at(q.x, q.y));  // NaN stays NaN for a NaN point
    ++n;
  }
  return n;
}

preprocess::GroundLabels objectGroundLabels(const std::vector<ScanPoint>& pts, const ClusterParams& p) {
  preprocess::GroundLabels g = preprocess::segmentGroundWithHeights(pts, p.groundParams());
  fillUnknownHeights(pts, g.ground, p.ground.sensor_height_m, g.height_above_ground_m);
  return g;
}

OrientedBox fitLShape(const std::vector<Eigen::Vector2d>& xy, double step_rad) {
  OrientedBox b;
  if (xy.empty()) return b;
  const size_t stride = std::max<size_t>(1, xy.size() / kMaxFitPoints);
  std::vector<double> c1, c2;
  auto closeness = [&](double theta) {  // Zhang et al. 2017, Alg. 4
    const double co = std::cos(theta), si = std::sin(theta);
    c1.clear(), c2.clear();
    for (size_t i = 0; i < xy.size(); i += stride) {
      c1.push_back(co * xy[i].x() + si * xy[i].y());
      c2.push_back(-si * xy[i].x() + co * xy[i].y());
    }
    const auto [lo1, hi1] = std::minmax_element(c1.begin(), c1.end());
    const auto [lo2, hi2] = std::minmax_element(c2.begin(), c2.end());
    double beta = 0;
    for (size_t k = 0; k < c1.size(); ++k) {
      const double d1 = std::min(*hi1 - c1[k], c1[k] - *lo1), d2 = std::min(*hi2 - c2[k], c2[k] - *lo2);
      beta += 1.0 / std::max(std::min(d1, d2), kClosenessFloor_m);
    }
    return beta;
  };
  // Alg. 1 searches [0, pi/2) in steps of delta; here coarsely (kCoarseSteps x delta) first, then in
  // steps of delta around the best coarse angle: a third of the evaluations at 1 deg.
  double best = -1, best_theta = 0;
  const double coarse = kCoarseSteps * step_rad;
  for (double theta = 0; theta < M_PI / 2; theta += coarse) {
    const double b = closeness(theta);
    if (b > best) best = b, best_theta = theta;
  }
  const double centre = best_theta;
  for (double theta = centre - coarse + step_rad; theta < centre + coarse; theta += step_rad) {
    if (std::abs(theta - centre) < 1e-12) continue;
    const double b = closeness(theta);
    if (b > best) best = b, best_theta = theta;
  }
  best_theta = std::fmod(best_theta + M_PI / 2, M_PI / 2);  // the box is the same a quarter turn on
  // The box of every point at the best angle (Alg. 1, lines 9-13).
  const double co = std::cos(best_theta), si = std::sin(best_theta);
  double lo1 = std::numeric_limits<double>::max(), hi1 = -lo1, lo2 = lo1, hi2 = -lo1;
  for (const auto& q : xy) {
    const double a = co * q.x() + si * q.y(), c = -si * q.x() + co * q.y();
    lo1 = std::min(lo1, a), hi1 = std::max(hi1, a), lo2 = std::min(lo2, c), hi2 = std::max(hi2, c);
  }
  const double m1 = 0.5 * (lo1 + hi1), m2 = 0.5 * (lo2 + hi2);
  b.centre_m = {co * m1 - si * m2, si * m1 + co * m2};
  b.length_m = hi1 - lo1, b.width_m = hi2 - lo2, b.yaw_rad = best_theta;
  if (b.width_m > b.length_m) std::swap(b.length_m, b.width_m), b.yaw_rad += M_PI / 2;
  b.yaw_rad = std::fmod(b.yaw_rad, M_PI);
  return b;
}

std::vector<Object> segmentObjects(const std::vector<ScanPoint>& pts, bool has_rings, const std::vector<uint8_t>& ground,
                                   const std::vector<float>& height_above_ground_m, const ClusterParams& p,
                                   SegmentationStats* stats) {
  std::vector<uint32_t> cand;
  std::vector<float> height(pts.size(), 0.f);
  cand.reserve(pts.size());
  const double rmin2 = p.min_range_m * p.min_range_m, rmax2 = p.max_range_m * p.max_range_m;
  for (size_t i = 0; i < pts.size(); ++i) {
    const ScanPoint& q = pts[i];
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) continue;
    if (i < ground.size() && ground[i]) continue;
    const double r2 = double(q.x) * q.x + double(q.y) * q.y;
    if (r2 < rmin2 || r2 > rmax2) continue;
    const float hg = i < height_above_ground_m.size() ? height_above_ground_m[i] : NAN;
    const double h = std::isfinite(hg) ? double(hg) : q.z + p.ground.sensor_height_m;
    if (h < p.min_height_m || h > p.max_height_m) continue;
    height[i] = static_cast<float>(h);
    cand.push_back(static_cast<uint32_t>(i));
  }
  Labels label(pts.size(), -1);
  const int n = p.method == ClusterMethod::Dbscan                 ? dbscanComponents(pts, cand, p, label)
                : (has_rings && p.method == ClusterMethod::RangeImage) ? rangeImageComponents(pts, cand, p, label)
                                                                       : euclideanComponents(pts, cand, p, label);
  std::vector<std::vector<uint32_t>> members(static_cast<size_t>(n));
  for (uint32_t i : cand) {
    if (label[i] >= 0) members[static_cast<size_t>(label[i])].push_back(i);  // DBSCAN's noise is -1
  }
  std::vector<Object> out;
  std::vector<Eigen::Vector2d> xy;
  for (auto& m : members) {
    if (m.size() < static_cast<size_t>(p.min_points)) continue;
    Object o;
    double z_min = std::numeric_limits<double>::max(), z_max = -z_min;
    xy.clear();
    for (uint32_t i : m) {
      const ScanPoint& q = pts[i];
      o.centroid += Eigen::Vector3d(q.x, q.y, q.z);
      o.t_mean += q.t;
      z_min = std::min<double>(z_min, q.z), z_max = std::max<double>(z_max, q.z);
      o.top_height_m = std::max<double>(o.top_height_m, height[i]);
      xy.emplace_back(q.x, q.y);
    }
    o.centroid /= static_cast<double>(m.size());
    o.t_mean /= static_cast<double>(m.size());
    if (o.top_height_m < p.min_top_height_m) continue;
    o.box = fitLShape(xy, p.lshape_step_rad);
    o.box.z_min_m = z_min, o.box.z_max_m = z_max;
    if (o.box.length_m > p.max_length_m || o.box.width_m > p.max_width_m) continue;
    o.points = m.size();
    o.indices = std::move(m);
    out.push_back(std::move(o));
  }
  if (stats) *stats = {cand.size(), static_cast<size_t>(n), out.size()};
  return out;
}

std::vector<Object> segmentSweep(const Scan& scan, const ClusterParams& p, SegmentationStats* stats) {
  const auto g = objectGroundLabels(scan.points, p);
  return segmentObjects(scan.points, scan.has_rings, g.ground, g.height_above_ground_m, p, stats);
}

}  // namespace roadslam::objects
