#include "roadslam/eval/boundary_metrics.h"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace roadslam::eval {
namespace {

using Polylines = std::vector<std::vector<Eigen::Vector2d>>;
using Polylines3 = std::vector<std::vector<Eigen::Vector3d>>;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// GT pose at \p t: linear position and slerped rotation between the bracketing poses, one of
/// which lies within \p max_dt.
bool poseAt(const datasets::Trajectory& gt, double t, double max_dt, Eigen::Isometry3d& T) {
  const auto& st = gt.stamps_s;
  if (st.empty()) return false;
  const size_t k = static_cast<size_t>(std::lower_bound(st.begin(), st.end(), t) - st.begin());
  if (k == 0 || k == st.size()) {
    const size_t j = k == 0 ? 0 : st.size() - 1;
    if (std::abs(st[j] - t) > max_dt) return false;
    T = gt.poses[j];
    return true;
  }
  if (std::min(t - st[k - 1], st[k] - t) > max_dt) return false;  // a gap in the GT
  const double u = (t - st[k - 1]) / (st[k] - st[k - 1]);
  const Eigen::Quaterniond qa(gt.poses[k - 1].linear()), qb(gt.poses[k].linear());
  T = Eigen::Isometry3d::Identity();
  T.linear() = qa.slerp(u, qb).toRotationMatrix();
  T.translation() = (1 - u) * gt.poses[k - 1].translation() + u * gt.poses[k].translation();
  return true;
}

Polylines toVehicle(const Polylines3& world, const Eigen::Isometry3d& T_world_lidar, double reach) {
  const Eigen::Isometry3d T_lidar_world = T_world_lidar.inverse();
  const Eigen::Vector2d c = T_world_lidar.translation().head<2>();
  Polylines out;
  for (const auto& l : world) {
    std::vector<Eigen::Vector2d> v;
    for (const auto& q : l) {
      if ((q.head<2>() - c).norm() > reach) {  // keep runs near the vehicle only: cheap and exact enough
        if (v.size() >= 2) out.push_back(v);
        v.clear();
        continue;
      }
      const Eigen::Vector3d p = T_lidar_world * (std::isnan(q.z()) ? Eigen::Vector3d(q.x(), q.y(), T_world_lidar.translation().z()) : q);
      v.emplace_back(p.x(), p.y());
    }
    if (v.size() >= 2) out.push_back(v);
  }
  return out;
}

/// [[x, y(, z)]]; a missing z is NaN (taken at the vehicle's height).
std::vector<Eigen::Vector3d> readPolyline(const nlohmann::json& a) {
  std::vector<Eigen::Vector3d> v;
  for (const auto& q : a) v.emplace_back(q.at(0).get<double>(), q.at(1).get<double>(), q.size() > 2 ? q.at(2).get<double>() : kNaN);
  return v;
}

/// The estimate's own pose of the frame (`T_map_lidar`, row-major 4x4): its polylines are in its map
/// frame, which is the GT world only when the job ran on GT poses.
bool estimatePose(const nlohmann::json& f, Eigen::Isometry3d& T) {
  if (!f.contains("T_map_lidar")) return false;
  const auto& a = f.at("T_map_lidar");
  if (!a.is_array() || a.size() != 16) throw std::runtime_error("T_map_lidar must hold 16 numbers");
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(r, c) = a.at(static_cast<size_t>(4 * r + c)).get<double>();
  T.matrix() = M;
  return M.allFinite();
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * v.size())) - 1);
  return v[k];
}

}  // namespace

Polylines3 readGtCurbs(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot open ground-truth boundaries '" + path + "'");
  Polylines3 out;
  try {
    const auto j = nlohmann::json::parse(f);
    for (const auto& road : j.at("roads"))
      for (const char* side : {"left_curbs", "right_curbs"})
        for (const auto& l : road.at(side)) out.push_back(readPolyline(l));
  } catch (const std::exception& e) {
    throw std::runtime_error("'" + path + "': " + e.what());
  }
  return out;
}

double lateralAt(const Polylines& pl, double x, int side, double max_lateral) {
  return lateralAlong(pl, Eigen::Vector2d(x, 0.0), Eigen::Vector2d::UnitY(), side, max_lateral);
}

double lateralAlong(const Polylines& pl, const Eigen::Vector2d& o, const Eigen::Vector2d& n, int side,
                    double max_lateral) {
  double best = kNaN;
  for (const auto& l : pl) {
    for (size_t i = 1; i < l.size(); ++i) {
      // o + lambda n = a + mu (b - a), mu in [0, 1] (Cramer's rule)
      const Eigen::Vector2d d = l[i] - l[i - 1], r = l[i - 1] - o;
      const double det = d.x() * n.y() - d.y() * n.x();
      if (std::abs(det) < 1e-12) continue;
      const double lambda = (d.x() * r.y() - d.y() * r.x()) / det;
      const double mu = (n.x() * r.y() - n.y() * r.x()) / det;
      if (mu < 0 || mu > 1 || side * lambda <= 0 || std::abs(lambda) > max_lateral) continue;
      if (std::isnan(best) || std::abs(lambda) < std::abs(best)) best = lambda;
    }
  }
  return best;
}

namespace {

struct Station {
  Eigen::Vector2d origin, normal;  ///< vehicle frame
};

/// The GT path after time \p t, up to \p length, in the vehicle frame of \p T: a polyline from the origin.
std::vector<Eigen::Vector2d> pathAhead(const datasets::Trajectory& gt, const Eigen::Isometry3d& T, double t,
                                       double length) {
  const Eigen::Isometry3d T_inv = T.inverse();
  std::vector<Eigen::Vector2d> path{Eigen::Vector2d::Zero()};
  double s = 0;
  const auto& st = gt.stamps_s;
  for (size_t k = static_cast<size_t>(std::upper_bound(st.begin(), st.end(), t) - st.begin());
       k < gt.poses.size() && s <= length; ++k) {
    const Eigen::Vector2d p = (T_inv * gt.poses[k].translation()).head<2>();
    const double ds = (p - path.back()).norm();
    if (ds < 0.05) continue;  // standing: no direction
    s += ds;
    path.push_back(p);
  }
  return path;
}

std::vector<Station> stationsFor(const datasets::Trajectory& gt, const Eigen::Isometry3d& T, double t,
                                 const BoundaryEvalParams& p) {
  std::vector<Station> out;
  std::vector<Eigen::Vector2d> path{Eigen::Vector2d::Zero(), Eigen::Vector2d::UnitX()};
  if (p.stations == "path") {
    path = pathAhead(gt, T, t, p.band_max_x_m);
    if (path.size() < 2) path.push_back(Eigen::Vector2d::UnitX());  // standing to the end: straight on
  }
  size_t seg = 1;
  double s0 = 0;  // arc length at path[seg - 1]
  for (double s = p.band_min_x_m; s <= p.band_max_x_m + 1e-9; s += p.station_step_m) {
    while (seg + 1 < path.size() && s0 + (path[seg] - path[seg - 1]).norm() < s) {
      s0 += (path[seg] - path[seg - 1]).norm();
      ++seg;
    }
    const Eigen::Vector2d u = (path[seg] - path[seg - 1]).normalized();
    out.push_back({path[seg - 1] + (s - s0) * u, Eigen::Vector2d(-u.y(), u.x())});  // past the end: straight on
  }
  return out;
}

}  // namespace

BoundaryMetrics evaluateBoundaries(const Polylines3& curbs, const datasets::Trajectory& gt,
                                   const std::vector<nlohmann::json>& est, const BoundaryEvalParams& p) {
  if (p.stations != "path" && p.stations != "axis") {
    throw std::invalid_argument("boundary eval: stations must be 'path' or 'axis', not '" + p.stations + "'");
  }
  BoundaryMetrics m;
  std::vector<double> errors;
  const double reach = std::hypot(p.band_max_x_m, p.max_lateral_m) + 20.0;
  for (const auto& f : est) {
    ++m.frames;
    m.per_frame.emplace_back();
    BoundaryFrameScore& fs = m.per_frame.back();
    if (f.contains("stamp_s")) fs.stamp_s = f.at("stamp_s").get<double>();
    if (!f.contains("left") || !f.contains("right")) continue;  // e.g. frames without a pose
    Eigen::Isometry3d T;
    if (!poseAt(gt, f.at("stamp_s").get<double>(), p.max_dt_s, T)) continue;
    const Polylines gt_v = toVehicle(curbs, T, reach);
    Eigen::Isometry3d T_est = T;
    if (!p.est_in_gt_frame) estimatePose(f, T_est);
    const auto stations = stationsFor(gt, T, f.at("stamp_s").get<double>(), p);
    bool both_gt = true, both_found = true;
    for (int side : {+1, -1}) {
      const auto& s = f.at(side > 0 ? "left" : "right");
      Polylines est_v;
      if (s.at("found").get<bool>()) est_v = toVehicle({readPolyline(s.at("polyline_map"))}, T_est, reach);
      int gt_n = 0, both_n = 0;
      std::vector<double> e;
      for (const auto& st : stations) {
        const double yg = lateralAlong(gt_v, st.origin, st.normal, side, p.max_lateral_m);
        if (std::isnan(yg)) continue;
        ++gt_n;
        const double ye = lateralAlong(est_v, st.origin, st.normal, side, p.max_lateral_m);
        if (std::isnan(ye)) continue;
        ++both_n;
        e.push_back(std::abs(ye - yg));
      }
      const bool gt_side = gt_n > 0;
      const bool found = gt_side && both_n >= p.min_coverage * gt_n;
      both_gt = both_gt && gt_side;
      both_found = both_found && found;
      if (gt_side && found) (side > 0 ? m.left_detected : m.right_detected) += 1;
      if (gt_side) errors.insert(errors.end(), e.begin(), e.end());
      const int k = side > 0 ? 0 : 1;
      fs.found[k] = found;
      fs.gt_stations[k] = gt_n;
      for (double x : e) fs.error_mean_m[k] += x / e.size(), fs.error_max_m[k] = std::max(fs.error_max_m[k], x);
    }
    if (!both_gt) continue;
    fs.scored = true;
    ++m.frames_scored;
    m.both_detected += both_found;
  }
  const double n = std::max(1, m.frames_scored);
  m.detection_rate = m.both_detected / n;
  m.left_detection_rate = m.left_detected / n;
  m.right_detection_rate = m.right_detected / n;
  m.stations = static_cast<int>(errors.size());
  if (!errors.empty()) {
    double sum = 0;
    for (double e : errors) sum += e, m.lateral_error_max_m = std::max(m.lateral_error_max_m, e);
    m.lateral_error_mean_m = sum / errors.size();
    m.lateral_error_p95_m = percentile(errors, 0.95);
  }
  return m;
}

BoundaryMetrics evaluateBoundaryFiles(const std::string& gt_boundaries, const std::string& gt_trajectory,
                                      const std::string& est_jsonl, const BoundaryEvalParams& p) {
  const auto curbs = readGtCurbs(gt_boundaries);
  const auto gt = datasets::readTum(gt_trajectory);
  std::ifstream f(est_jsonl);
  if (!f) throw std::runtime_error("cannot open estimate '" + est_jsonl + "'");
  std::vector<nlohmann::json> est;
  std::string line;
  for (int ln = 1; std::getline(f, line); ++ln) {
    if (line.empty()) continue;
    try {
      est.push_back(nlohmann::json::parse(line));
    } catch (const std::exception& e) {
      throw std::runtime_error(est_jsonl + ":" + std::to_string(ln) + ": " + e.what());
    }
  }
  return evaluateBoundaries(curbs, gt, est, p);
}

nlohmann::json toJson(const BoundaryMetrics& m) {
  return {{"frames", m.frames}, {"frames_scored", m.frames_scored}, {"detection_rate", m.detection_rate},
          {"left_detection_rate", m.left_detection_rate}, {"right_detection_rate", m.right_detection_rate},
          {"stations", m.stations}, {"lateral_error_mean_m", m.lateral_error_mean_m},
          {"lateral_error_p95_m", m.lateral_error_p95_m}, {"lateral_error_max_m", m.lateral_error_max_m}};
}

std::string perFrameCsv(const BoundaryMetrics& m) {
  std::ostringstream s;
  s << "stamp_s,scored,left_found,left_gt_stations,left_error_mean_m,left_error_max_m,"
       "right_found,right_gt_stations,right_error_mean_m,right_error_max_m\n";
  s.precision(10);
  char stamp[64];
  for (const auto& f : m.per_frame) {
    std::snprintf(stamp, sizeof stamp, "%.9f", f.stamp_s);  // fixed: epoch stamps keep their microseconds
    s << stamp << ',' << f.scored;
    for (int k : {0, 1}) s << ',' << f.found[k] << ',' << f.gt_stations[k] << ',' << f.error_mean_m[k] << ',' << f.error_max_m[k];
    s << '\n';
  }
  return s.str();
}

std::string toText(const BoundaryMetrics& m) {
  std::ostringstream s;
  s << "frames " << m.frames << " (scored " << m.frames_scored << ")\n"
    << "detection_rate " << m.detection_rate << " (left " << m.left_detection_rate << ", right "
    << m.right_detection_rate << ")\n"
    << "lateral_error_mean_m " << m.lateral_error_mean_m << "\nlateral_error_p95_m " << m.lateral_error_p95_m
    << "\nlateral_error_max_m " << m.lateral_error_max_m << " over " << m.stations << " stations\n";
  return s.str();
}

}  // namespace roadslam::eval
