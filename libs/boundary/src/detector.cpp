// Orchestration of one sweep: labels -> obstacles -> free space -> boundaries -> cost grid.
#include "roadslam/boundary/detector.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_set>

#include "internal.h"
#include "roadslam/objects/segmentation.h"

namespace roadslam::boundary {
namespace {

/// The objects segmentation run as the obstacle clustering: the labelling picks the points (its
/// obstacles; the thesis method, every non-ground point of known height), the objects' size and
/// height filters are off (walls, hedges and poles are obstacles too).
objects::ClusterParams obstacleClusterParams(const Params& p) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  objects::ClusterParams c;
  c.method = p.cluster_method;
  c.cluster_distance_m = p.cluster_distance_m;
  c.min_points = p.cluster_min_points;
  c.min_height_m = c.min_top_height_m = -kInf;
  c.max_height_m = c.max_range_m = c.max_length_m = c.max_width_m = kInf;
  c.min_range_m = 0;
  c.ground = p.ground;
  return c;
}

std::vector<Obstacle> clusterObstacles(const Scan& scan, const Labelling& lab, const Params& p, bool with_low) {
  const size_t n = scan.points.size();  // the sweep's points only (see process())
  std::vector<uint8_t> left_out(n, 1);  // segmentObjects' "ground" mask: 1 = not an obstacle point
  for (size_t i = 0; i < n; ++i) {
    left_out[i] = !(lab.cls[i] == PointClass::Obstacle ||
                    (with_low && lab.cls[i] != PointClass::Ground && std::isfinite(lab.height_m[i])));
  }
  const std::vector<float> heights(lab.height_m.begin(), lab.height_m.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<Obstacle> out;
  for (const objects::Object& ob : objects::segmentObjects(scan.points, scan.has_rings, left_out, heights, obstacleClusterParams(p))) {
    Obstacle o;
    std::vector<Vec2> cp;
    cp.reserve(ob.indices.size());
    for (uint32_t i : ob.indices) cp.push_back({scan.points[i].x, scan.points[i].y});
    o.points = static_cast<int>(ob.points);
    o.max_height_m = ob.top_height_m;
    o.hull = detail::convexHull(std::move(cp));
    o.center = {ob.box.centre_m.x(), ob.box.centre_m.y()};
    o.length_m = ob.box.length_m, o.width_m = ob.box.width_m;
    o.yaw_rad = std::remainder(ob.box.yaw_rad, M_PI);  // a rectangle's direction is defined modulo pi
    out.push_back(std::move(o));
  }
  return out;
}

/// Polar free space (where a laser passed, nothing stands): per sector, up to the nearest curb or
/// obstacle point, and no farther than the farthest return seen in it.
std::vector<double> freeRanges(const Scan& scan, const Labelling& lab, const Params& p) {
  const int ns = p.freespace_sectors;
  std::vector<double> blocked(ns, std::numeric_limits<double>::infinity()), seen(ns, 0.0);
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const auto& q = scan.points[i];
    const double r = std::hypot(q.x, q.y);
    if (!(r <= p.roi_range_m)) continue;
    const int s = std::clamp(static_cast<int>((std::atan2(q.y, q.x) + M_PI) / (2 * M_PI) * ns), 0, ns - 1);
    seen[s] = std::max(seen[s], r);
    if (lab.cls[i] == PointClass::Curb || lab.cls[i] == PointClass::Obstacle) blocked[s] = std::min(blocked[s], r);
  }
  for (int s = 0; s < ns; ++s) blocked[s] = std::min(blocked[s], seen[s]);
  return blocked;
}

void fillGrid(const Params& p, const std::vector<double>& free_r, const BoundaryFrame& f, CostGrid& g) {
  g.resolution_m = p.grid_resolution_m;
  g.nx = g.ny = static_cast<int>(std::ceil(p.grid_size_m / p.grid_resolution_m));
  g.x0_m = 15.0 - 0.5 * p.grid_size_m;  // centred 15 m ahead: the planner looks forward
  g.y0_m = -0.5 * p.grid_size_m;
  g.cost.assign(static_cast<size_t>(g.nx) * g.ny, CostGrid::kUnknown);
  const int ns = static_cast<int>(free_r.size());
  auto put = [&](double x, double y, uint8_t c) {
    const int i = static_cast<int>(std::floor((x - g.x0_m) / g.resolution_m));
    const int j = static_cast<int>(std::floor((y - g.y0_m) / g.resolution_m));
    // Curb and obstacle costs exceed kUnknown and kFree: the max keeps the most severe.
    if (i >= 0 && j >= 0 && i < g.nx && j < g.ny) g.cost[static_cast<size_t>(j) * g.nx + i] = std::max(g.cost[static_cast<size_t>(j) * g.nx + i], c);
  };
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.x0_m + (i + 0.5) * g.resolution_m, y = g.y0_m + (j + 0.5) * g.resolution_m;
      const int s = std::clamp(static_cast<int>((std::atan2(y, x) + M_PI) / (2 * M_PI) * ns), 0, ns - 1);
      if (std::hypot(x, y) < free_r[s]) g.cost[static_cast<size_t>(j) * g.nx + i] = CostGrid::kFree;
    }
  }
  for (const auto& c : f.curb_points) put(c.x, c.y, CostGrid::kCurb);
  for (const SideBoundary* sb : {&f.left, &f.right})
    for (const auto& v : sb->polyline_vehicle) put(v.x, v.y, CostGrid::kCurb);
  for (const auto& o : f.obstacles)
    for (const auto& v : o.hull) put(v.x, v.y, CostGrid::kObstacle);
}

/// Map-frame points (one per curb-map cell) within curb_veto_range_m that stand tall_height_m to
/// tall_max_height_m above the local ground: the labelling's "tall" points, which no curb may
/// neighbour.
std::vector<Eigen::Vector3d> tallPointsInMap(const Scan& scan, const Labelling& lab, const Eigen::Isometry3d& T_map_lidar,
                                             const Params& p) {
  std::vector<Eigen::Vector3d> out;
  std::unordered_set<int64_t> seen;
  const double r2max = p.curb_veto_range_m * p.curb_veto_range_m;
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const auto& q = scan.points[i];
    const float h = lab.height_m[i];
    if (!detail::standsTall(lab.cls[i] == PointClass::Ground, h, p) || !(q.x * q.x + q.y * q.y <= r2max))
      continue;
    const Eigen::Vector3d m = T_map_lidar * Eigen::Vector3d(q.x, q.y, q.z);
    if (seen.insert(detail::cellKey(m.x(), m.y(), p.curb_map_cell_m)).second) out.push_back(m);
  }
  return out;
}

/// The curb points of \p scan, map frame.
std::vector<Eigen::Vector3d> curbPointsInMap(const Scan& scan, const Labelling& lab, const Eigen::Isometry3d& T_map_lidar) {
  std::vector<Eigen::Vector3d> out;
  for (size_t i = 0; i < scan.points.size(); ++i) {
    if (lab.cls[i] != PointClass::Curb) continue;
    const auto& q = scan.points[i];
    out.push_back(T_map_lidar * Eigen::Vector3d(q.x, q.y, q.z));
  }
  return out;
}

double yawOf(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

/// The points of \p pts within \p gate (lateral) of the polyline \p line (vertices ascending in x).
std::vector<Vec2> nearLine(const std::vector<Vec2>& pts, const std::vector<Vec2>& line, double gate) {
  std::vector<Vec2> out;
  for (const auto& q : pts) {
    const auto it = std::lower_bound(line.begin(), line.end(), q.x, [](const Vec2& v, double x) { return v.x < x; });
    if (it == line.begin() || it == line.end()) continue;
    const Vec2 &a = *(it - 1), &b = *it;
    const double y = b.x > a.x ? a.y + (b.y - a.y) * (q.x - a.x) / (b.x - a.x) : a.y;
    if (std::abs(q.y - y) <= gate) out.push_back(q);
  }
  return out;
}

/// Vertices on the road surface, so a rolled or pitched sensor does not shift them in the map.
void toMap(const Eigen::Isometry3d& T_map_lidar, double sensor_height, SideBoundary& s) {
  for (const auto& v : s.polyline_vehicle) {
    const Eigen::Vector3d m = T_map_lidar * Eigen::Vector3d(v.x, v.y, -sensor_height);
    s.polyline_map.push_back({m.x(), m.y(), m.z()});
  }
}

}  // namespace

BoundaryDetector::BoundaryDetector(Params p) : p_(std::move(p)), curb_map_(p_.curb_map_cell_m) {}

double BoundaryDetector::pathCurvature(const Eigen::Isometry3d& T_map_lidar) {
  path_.push_back(T_map_lidar);
  while (path_.size() > static_cast<size_t>(std::max(0, p_.path_curvature_frames)) + 1) path_.pop_front();
  if (path_.size() < 2) return 0;
  double len = 0;
  for (size_t i = 1; i < path_.size(); ++i) len += (path_[i].translation() - path_[i - 1].translation()).head<2>().norm();
  if (len < p_.path_min_length_m) return 0;
  return std::remainder(yawOf(path_.back()) - yawOf(path_.front()), 2 * M_PI) / len;
}

SideBoundary BoundaryDetector::track(SideBoundary fresh, const std::vector<Vec2>& pts, int side, std::mt19937& rng,
                                     Track& tr, const Eigen::Isometry3d& T_map_lidar,
                                     const detail::BendFrame& arc) const {
  auto toMapPt = [&](const Vec2& a) {
    const Vec2 v = arc.toXY(a);
    return T_map_lidar * Eigen::Vector3d(v.x, v.y, -p_.ground.sensor_height_m);
  };
  const std::vector<Vec2> held = heldPoints(tr, T_map_lidar, arc);  // the track in the current arc frame
  if (fresh.found && !held.empty()) {
    int n = 0;
    double dev = detail::deviationInBand(fresh.polyline_vehicle, held, p_, &n);
    // Continuity: while the curb map still supports the tracked line, a fit elsewhere (a sidewalk's
    // far edge gathering more bins over many sweeps) does not replace it.
    if (n > 0 && dev > p_.track_gate_m) {
      SideBoundary alt = detail::fitSide(nearLine(pts, held, p_.track_gate_m), side, p_, rng);
      if (alt.found) fresh = std::move(alt), dev = 0;
    }
    // Only a better-supported track may veto a fit: a weak track must not lock out the real curb.
    if (n > 0 && dev > p_.track_gate_m && tr.held < p_.max_hold_frames && fresh.confidence < tr.confidence) {
      fresh.found = false;
      fresh.reason = "fit jumped " + std::to_string(dev).substr(0, 4) + " m from the tracked boundary";
    }
  }
  if (fresh.found) {
    tr.map_pts.clear();
    const double x0 = fresh.polyline_vehicle.front().x;
    for (double x = p_.fit_min_x_m; x < x0 - 1e-9; x += p_.polyline_step_m)  // the fit behind the band
      tr.map_pts.push_back(toMapPt({x, detail::polyEval(fresh.coeffs, x)}));
    for (const auto& v : fresh.polyline_vehicle) tr.map_pts.push_back(toMapPt(v));
    tr.confidence = fresh.confidence, tr.held = 0, tr.valid = true, tr.yaw_map = yawOf(T_map_lidar);
    return fresh;
  }
  // A held line is a straight-ahead prediction: through a corner it would cut across the turn.
  const double turned = tr.valid ? std::abs(std::remainder(yawOf(T_map_lidar) - tr.yaw_map, 2 * M_PI)) : 0.0;
  if (!tr.valid || tr.held >= p_.max_hold_frames || turned > p_.hold_max_turn_rad) {
    if (tr.valid && turned > p_.hold_max_turn_rad)
      fresh.reason += " (track dropped: the vehicle turned " + std::to_string(static_cast<int>(turned * 180 / M_PI)) + " deg)";
    tr.valid = false;
    return fresh;
  }
  ++tr.held;
  SideBoundary out = fresh;
  out.polyline_vehicle.clear();
  for (const auto& h : held)
    if (h.x >= p_.band_min_x_m && h.x <= p_.band_max_x_m) out.polyline_vehicle.push_back(h);
  out.found = out.polyline_vehicle.size() >= 2;
  out.confidence = tr.confidence * std::pow(p_.hold_decay, tr.held);
  out.reason = (out.found ? "held " + std::to_string(tr.held) + " sweeps: " : "held track left the band: ") + fresh.reason;
  return out;
}

std::vector<Vec2> BoundaryDetector::heldPoints(const Track& tr, const Eigen::Isometry3d& T_map_lidar,
                                               const detail::BendFrame& arc, bool stale) const {
  std::vector<Vec2> held;
  if (!tr.valid && !stale) return held;
  const Eigen::Isometry3d T_lidar_map = T_map_lidar.inverse();
  for (const auto& m : tr.map_pts) {
    const Eigen::Vector3d v = T_lidar_map * m;
    Vec2 a;
    if (arc.toArc({v.x(), v.y()}, a)) held.push_back(a);
  }
  return held;
}

void BoundaryDetector::fitSides(const Eigen::Isometry3d& T_map_lidar, std::mt19937& rng, BoundaryFrame& f) {
  const double kappa = pathCurvature(T_map_lidar);
  detail::BendFrame arc;
  detail::PathFrame drive_path;
  const std::vector<Vec2> cells = fitCells(T_map_lidar);
  if (whole_drive_) {
    const auto it = std::lower_bound(drive_stamps_s_.begin(), drive_stamps_s_.end(), f.stamp_s);
    size_t k = std::min<size_t>(it - drive_stamps_s_.begin(), drive_stamps_s_.size() - 1);
    if (k > 0 && f.stamp_s - drive_stamps_s_[k - 1] < drive_stamps_s_[k] - f.stamp_s) --k;
    drive_path = detail::pathAround(drive_pos_, k, T_map_lidar, -p_.fit_min_x_m, p_.fit_max_x_m, p_.path_step_m);
    arc.path = &drive_path;
  } else {
    arc = detail::chooseFrame(cells, kappa, p_);
  }
  f.path_curvature = kappa;
  f.bend_s = arc.bent() ? arc.s_bend : -1.0;
  f.bend_curvature = arc.bent() ? arc.b.kappa : kappa;
  std::vector<Vec2> pts;  // the curb map's cells in the fit frame
  for (const auto& q : cells) {
    Vec2 a;
    if (arc.toArc(q, a)) pts.push_back(a);
  }
  // Up to completeParallel a side is found only by its own fit (fitSide, or checkWidth's refit), so
  // `found` here means "fitted from this sweep's curb map", never continued or held.
  SideBoundary l = detail::fitSide(pts, +1, p_, rng), r = detail::fitSide(pts, -1, p_, rng);
  const bool width_known = road_width_m_ > 0 && f.index - road_width_frame_ <= static_cast<size_t>(p_.memory_frames);
  // The width of the pair as fitted: a new width is adopted once it persists (updateWidth), even
  // while checkWidth rejects one side of it.
  const double w_fit = l.found && r.found ? detail::parallelOffset(r, l, pts, -1, p_)
                                          : std::numeric_limits<double>::quiet_NaN();
  if (width_known && p_.width_jump_m > 0 && l.found && r.found) checkWidth(l, r, pts, rng, T_map_lidar, arc);
  updateWidth(w_fit, width_known, f.index);
  // Each side from the other's own fit only: a continued side never continues the other one.
  const SideBoundary l_own = l;
  const double width = width_known ? road_width_m_ : std::numeric_limits<double>::quiet_NaN();
  if (r.found) detail::completeParallel(l, r, pts, +1, p_, width);
  if (l_own.found) detail::completeParallel(r, l_own, pts, -1, p_, width);
  f.left = track(std::move(l), pts, +1, rng, tracks_[0], T_map_lidar, arc);
  f.right = track(std::move(r), pts, -1, rng, tracks_[1], T_map_lidar, arc);
  for (SideBoundary* sb : {&f.left, &f.right})
    for (auto& v : sb->polyline_vehicle) v = arc.toXY(v);
}

std::vector<Vec2> BoundaryDetector::fitCells(const Eigen::Isometry3d& T_map_lidar) const {
  if (whole_drive_)
    return curb_map_.inVehicle(T_map_lidar, p_.whole_drive_min_sightings, std::hypot(p_.fit_max_x_m, p_.max_lateral_m));
  return curb_map_.inVehicle(T_map_lidar, p_.curb_min_sightings);
}

void BoundaryDetector::accumulate(const Scan& scan, const Eigen::Isometry3d& T_map_lidar, double stamp_s) {
  if (whole_drive_) throw std::logic_error("BoundaryDetector::accumulate after finishAccumulation");
  if (!drive_stamps_s_.empty() && stamp_s < drive_stamps_s_.back())
    throw std::invalid_argument("BoundaryDetector::accumulate: sweeps out of time order");
  const Labelling lab = labelPoints(scan, p_);
  curb_map_.insert(curbPointsInMap(scan, lab, T_map_lidar), drive_stamps_s_.size());
  if (p_.curb_veto_cells >= 0) {
    const auto tall = tallPointsInMap(scan, lab, T_map_lidar, p_);
    // One per cell over the drive: a parked car stands in the same cells for hundreds of sweeps.
    for (const auto& m : tall)
      if (drive_tall_cells_.insert(detail::cellKey(m.x(), m.y(), p_.curb_map_cell_m)).second) drive_tall_.push_back(m);
  }
  drive_stamps_s_.push_back(stamp_s);
  drive_pos_.push_back(T_map_lidar.translation());
}

void BoundaryDetector::finishAccumulation() {
  // After all sweeps: a cell any sweep saw standing is dropped, whichever came first.
  curb_map_.erase(drive_tall_, p_.curb_veto_cells);
  drive_tall_ = {};
  drive_tall_cells_ = {};
  whole_drive_ = !drive_stamps_s_.empty();
}

BoundaryFrame BoundaryDetector::process(const Scan& scan, const Eigen::Isometry3d& T_map_lidar, double stamp_s,
                                        const std::vector<Eigen::Vector3f>* local_map_map) {
  const auto t0 = std::chrono::steady_clock::now();
  Scan with_map;  // the sweep followed by the local map's points near the vehicle, lidar frame
  if (local_map_map && !local_map_map->empty() && !scan.points.empty()) {
    with_map = scan;
    const Eigen::Isometry3f T_lidar_map = T_map_lidar.inverse().cast<float>();
    const float r2 = static_cast<float>(p_.curb_max_range_m * p_.curb_max_range_m);
    for (const auto& m : *local_map_map) {
      const Eigen::Vector3f v = T_lidar_map * m;
      if (v.x() * v.x() + v.y() * v.y() > r2) continue;
      ScanPoint q;
      q.x = v.x(), q.y = v.y(), q.z = v.z();
      with_map.points.push_back(q);
    }
  }
  const Scan& all = with_map.points.empty() ? scan : with_map;
  BoundaryFrame f;
  f.index = frames_++;
  f.stamp_s = stamp_s;
  f.T_map_lidar = T_map_lidar;
  f.points = scan.points.size();
  last_ = labelPoints(all, p_);
  f.ground_points = last_.ground;
  f.curb_count = last_.curb;
  f.obstacle_points = last_.obstacle;
  for (size_t i = 0; i < all.points.size(); ++i)
    if (last_.cls[i] == PointClass::Curb) f.curb_points.push_back({all.points[i].x, all.points[i].y});
  if (!whole_drive_) {
    curb_map_.insert(curbPointsInMap(all, last_, T_map_lidar), f.index);
    if (p_.curb_veto_cells >= 0) curb_map_.erase(tallPointsInMap(scan, last_, T_map_lidar, p_), p_.curb_veto_cells);
    curb_map_.prune(T_map_lidar, -p_.fit_min_x_m, p_.curb_map_radius_m, f.index, static_cast<size_t>(p_.memory_frames));
  }

  if (f.points == 0 || f.ground_points == 0) {
    f.status = f.points == 0 ? FrameStatus::NoPoints : FrameStatus::NoGround;
    const std::string why = f.points == 0 ? "no points in the sweep" : "no ground found: heights above the road unknown";
    f.left.reason = f.right.reason = why;
  } else {
    f.obstacles = clusterObstacles(scan, last_, p_, p_.method == Method::Thesis);
    std::mt19937 rng(static_cast<unsigned>(p_.ransac_seed));
    if (p_.method == Method::Thesis) {
      f.left = detail::fitSideThesis(f.obstacles, +1, p_, rng);
      f.right = detail::fitSideThesis(f.obstacles, -1, p_, rng);
    } else {
      fitSides(T_map_lidar, rng, f);
    }
    toMap(T_map_lidar, p_.ground.sensor_height_m, f.left);
    toMap(T_map_lidar, p_.ground.sensor_height_m, f.right);
    const auto free_r = freeRanges(scan, last_, p_);
    const int ns = p_.freespace_sectors;
    for (int s = 0; s < ns; ++s) {
      const double a = -M_PI + (s + 0.5) * 2 * M_PI / ns;
      f.free_space.push_back({free_r[s] * std::cos(a), free_r[s] * std::sin(a)});
    }
    fillGrid(p_, free_r, f, f.grid);
  }
  f.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return f;
}

}  // namespace roadslam::boundary
