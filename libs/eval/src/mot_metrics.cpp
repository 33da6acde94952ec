#include "roadslam/eval/mot_metrics.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/runfolder/objects_csv.h"

namespace roadslam::eval {
namespace {

constexpr long long kStampTolerance_us = 5;
constexpr int kWrapIdStep = 100000;      // GT id of a wrapped car's n-th re-entry: id + n * kWrapIdStep
constexpr double kWrapMinJump_m = 5.0;  // a step this much longer than the speed allows is a wrap

struct GtCar {
  int id = 0;
  std::vector<double> t, x, y;
  std::vector<int> returns;  ///< per sample, -1 when the file has none
};

struct Hyp {
  int id = 0;
  Eigen::Vector2d p_map, v_map;
  bool moving = false;
  double age_s = 0;
};

std::vector<GtCar> readGtCars(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read '" + path + "'");
  const auto j = nlohmann::json::parse(f, nullptr, false);
  if (j.is_discarded() || !j.contains("moving_cars")) throw std::runtime_error("'" + path + "' is no gt_objects.json");
  std::vector<GtCar> out;
  for (const auto& c : j["moving_cars"]) {
    GtCar g;
    g.id = c["id"].get<int>();
    // The simulator's open roads wrap (sim World::carPose): a car that leaves at one end re-enters at
    // the other under its id, hundreds of metres away one sample later. That is another car to a
    // tracker, and CLEAR MOT would count the id it cannot carry as a switch: the track is split where
    // a step is longer than the car's speed allows, the pieces numbered id + kWrapIdStep * n.
    const double speed = std::abs(c.value("speed_mps", 1e9));
    int piece = 0;
    for (const auto& s : c["track"]) {
      const double t = s[0].get<double>(), x = s[1].get<double>(), y = s[2].get<double>();
      if (!g.t.empty() && std::hypot(x - g.x.back(), y - g.y.back()) > 2 * speed * (t - g.t.back()) + kWrapMinJump_m) {
        if (g.t.size() >= 2) out.push_back(g);
        g = GtCar{};
        g.id = c["id"].get<int>() + kWrapIdStep * ++piece;
      }
      g.t.push_back(t), g.x.push_back(x), g.y.push_back(y);
      g.returns.push_back(s.size() > 5 ? s[5].get<int>() : -1);
    }
    if (g.t.size() >= 2) out.push_back(std::move(g));
  }
  return out;
}

/// Linear interpolation of the car at \p t (position and velocity from the bracketing samples);
/// false outside its track.
bool carAt(const GtCar& c, double t, Eigen::Vector2d& p, Eigen::Vector2d& v) {
  if (t < c.t.front() || t > c.t.back()) return false;
  const size_t k = std::min<size_t>(c.t.size() - 1,
                                    std::max<size_t>(1, std::upper_bound(c.t.begin(), c.t.end(), t) - c.t.begin()));
  const double dt = c.t[k] - c.t[k - 1], u = (t - c.t[k - 1]) / dt;
  p = {(1 - u) * c.x[k - 1] + u * c.x[k], (1 - u) * c.y[k - 1] + u * c.y[k]};
  v = {(c.x[k] - c.x[k - 1]) / dt, (c.y[k] - c.y[k - 1]) / dt};
  return true;
}

/// The car's returns in the sample nearest to \p t (-1 unknown).
int returnsAt(const GtCar& c, double t) {
  const size_t k = std::upper_bound(c.t.begin(), c.t.end(), t) - c.t.begin();
  if (k == 0) return c.returns.front();
  if (k >= c.t.size()) return c.returns.back();
  return (t - c.t[k - 1] < c.t[k] - t) ? c.returns[k - 1] : c.returns[k];
}

/// The pose of \p tr at \p t (linear translation, slerp rotation); false outside it.
bool poseAt(const datasets::Trajectory& tr, double t, Eigen::Isometry3d& T) {
  const auto& s = tr.stamps_s;
  if (s.empty() || t < s.front() - 1e-6 || t > s.back() + 1e-6) return false;
  const size_t k = std::min<size_t>(s.size() - 1, std::max<size_t>(1, std::upper_bound(s.begin(), s.end(), t) - s.begin()));
  if (s.size() == 1) {
    T = tr.poses[0];
    return true;
  }
  const double u = std::clamp((t - s[k - 1]) / (s[k] - s[k - 1]), 0.0, 1.0);
  const Eigen::Quaterniond q0(tr.poses[k - 1].linear()), q1(tr.poses[k].linear());
  T = Eigen::Isometry3d::Identity();
  T.linear() = q0.slerp(u, q1).toRotationMatrix();
  T.translation() = (1 - u) * tr.poses[k - 1].translation() + u * tr.poses[k].translation();
  return true;
}

/// T_map_world at \p t: the run's pose (\p est, T_map_lidar) composed with the GT's inverse (\p gt,
/// T_world_lidar), both at \p t clamped into the run's and the GT's spans.
Eigen::Isometry3d mapFromWorld(const datasets::Trajectory& gt, const datasets::Trajectory& est, double t) {
  const double te = std::clamp(t, est.stamps_s.front(), est.stamps_s.back());
  const double tg = gt.stamps_s.empty() ? te : std::clamp(te, gt.stamps_s.front(), gt.stamps_s.back());
  Eigen::Isometry3d T_map_lidar, T_world_lidar;
  poseAt(est, te, T_map_lidar);
  if (!poseAt(gt, tg, T_world_lidar)) T_world_lidar = Eigen::Isometry3d::Identity();
  return T_map_lidar * T_world_lidar.inverse();
}

/// tracks.csv rows grouped by their time (rounded to the microsecond).
std::map<long long, std::vector<Hyp>> readTracks(const std::string& path) {
  if (!std::ifstream(path)) throw std::runtime_error("cannot read '" + path + "' (roadslam-map with [objects] enabled = true writes it)");
  std::map<long long, std::vector<Hyp>> out;
  for (const runfolder::TrackRow& r : runfolder::readTracksCsv(path)) {
    Hyp h;
    h.id = r.track_id;
    h.p_map = r.box.centre_m, h.v_map = {r.vx, r.vy};
    h.moving = r.moving, h.age_s = r.age_s;
    out[std::llround(r.stamp_s * 1e6)].push_back(h);
  }
  return out;
}

/// Greedy assignment in order of distance: the optimal one while the objects stand farther apart than
/// twice the gate, which holds for cars' centres with a 2 m gate.
std::vector<std::pair<size_t, size_t>> assign(const std::vector<Eigen::Vector2d>& g, const std::vector<Eigen::Vector2d>& h,
                                              const std::vector<char>& g_free, const std::vector<char>& h_free, double thr) {
  std::vector<std::tuple<double, size_t, size_t>> pairs;
  for (size_t i = 0; i < g.size(); ++i) {
    for (size_t j = 0; j < h.size(); ++j) {
      if (!g_free[i] || !h_free[j]) continue;
      const double d = (g[i] - h[j]).norm();
      if (d <= thr) pairs.emplace_back(d, i, j);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> gu(g.size(), 0), hu(h.size(), 0);
  std::vector<std::pair<size_t, size_t>> out;
  for (const auto& [d, i, j] : pairs) {
    if (gu[i] || hu[j]) continue;
    gu[i] = hu[j] = 1;
    out.emplace_back(i, j);
  }
  return out;
}

}  // namespace

MotMetrics evaluateMotFiles(const std::string& gt_objects_json, const std::string& gt_trajectory_tum,
                            const std::string& run_dir, const MotParams& p) {
  const auto cars = readGtCars(gt_objects_json);
  const auto gt_traj = datasets::readTum(gt_trajectory_tum);
  const auto est = datasets::readTum(run_dir + "/trajectory_odometry.tum");
  const auto tracks = readTracks(run_dir + "/tracks.csv");
  MotMetrics m;
  std::map<int, int> last_match;  // GT id -> hypothesis id of its last match
  std::map<int, double> last_match_t;  // GT id -> time of its last match [s]
  std::set<int> left_view;             // GT ids out of the sensor's view since their last match
  std::set<int> seen;
  std::vector<double> speed_err;
  double dist_sum = 0, prev_t = NAN;
  size_t moving_matches = 0;
  for (size_t k = 0; k < est.poses.size(); ++k) {
    const double t = est.stamps_s[k];
    Eigen::Isometry3d T_world_lidar;
    if (!poseAt(gt_traj, t, T_world_lidar)) continue;
    const Eigen::Isometry3d T_lidar_world = T_world_lidar.inverse(), T_lidar_map = est.poses[k].inverse();
    const double dt = std::isfinite(prev_t) ? std::min(t - prev_t, 0.5) : 0.1;
    prev_t = t;
    ++m.frames;
    // GT cars and hypotheses in the lidar frame of time t; dc: the don't-care cars (hidden or far)
    std::vector<Eigen::Vector2d> g, gv, h, hv, dc;
    std::vector<int> g_id, g_ret;
    for (const auto& c : cars) {
      Eigen::Vector2d pw, vw;
      if (!carAt(c, t, pw, vw)) {
        left_view.insert(c.id);
        continue;
      }
      const Eigen::Vector3d pl = T_lidar_world * Eigen::Vector3d(pw.x(), pw.y(), T_world_lidar.translation().z());
      const double r = pl.head<2>().norm();
      const int ret = returnsAt(c, t);
      if (r > p.max_range_m + p.dont_care_margin_m || ret == 0) left_view.insert(c.id);
      if (r > p.max_range_m + p.dont_care_margin_m) continue;
      if (r > p.max_range_m || (ret >= 0 && ret < p.min_returns)) {
        dc.push_back(pl.head<2>());
        continue;
      }
      g.push_back(pl.head<2>());
      gv.push_back((T_lidar_world.linear() * Eigen::Vector3d(vw.x(), vw.y(), 0)).head<2>());
      g_id.push_back(c.id);
      g_ret.push_back(ret);
      seen.insert(c.id);
    }
    m.dont_care += dc.size();
    std::vector<Hyp> hyps;
    // tracks.csv's %.6f stamp and the TUM file's 9 decimals can round apart by a microsecond at
    // epoch times (1e15 us: a double's step is 0.25 us): the nearest row time within 5 us
    auto it = tracks.lower_bound(std::llround(t * 1e6) - kStampTolerance_us);
    if (it != tracks.end() && std::abs(it->first - std::llround(t * 1e6)) > kStampTolerance_us) it = tracks.end();
    if (it != tracks.end()) {
      for (const Hyp& y : it->second) {
        const Eigen::Vector3d pl = T_lidar_map * Eigen::Vector3d(y.p_map.x(), y.p_map.y(), est.poses[k].translation().z());
        if (pl.head<2>().norm() > p.max_range_m + p.match_distance_m) continue;
        hyps.push_back(y);
        h.push_back(pl.head<2>());
        hv.push_back((T_lidar_map.linear() * Eigen::Vector3d(y.v_map.x(), y.v_map.y(), 0)).head<2>());
      }
    }
    m.gt += g.size();
    std::vector<char> g_free(g.size(), 1), h_free(h.size(), 1);
    std::vector<std::pair<size_t, size_t>> matched;
    // correspondences of the last frame that still hold (CLEAR MOT Sec. 2.1.1)
    for (size_t i = 0; i < g.size(); ++i) {
      const auto lm = last_match.find(g_id[i]);
      if (lm == last_match.end()) continue;
      for (size_t j = 0; j < h.size(); ++j) {
        if (h_free[j] && hyps[j].id == lm->second && (g[i] - h[j]).norm() <= p.match_distance_m) {
          matched.emplace_back(i, j), g_free[i] = h_free[j] = 0;
          break;
        }
      }
    }
    auto event = [&](const char* kind, int gi, int hj, double range, int ret, double nearest, double gap = -1, int left = -1) {
      if (p.keep_events) m.events.push_back({t, kind, gi, hj, range, ret, nearest, gap, left});
    };
    for (const auto& [i, j] : assign(g, h, g_free, h_free, p.match_distance_m)) {
      matched.emplace_back(i, j), g_free[i] = h_free[j] = 0;
      const auto lm = last_match.find(g_id[i]);
      if (lm != last_match.end() && lm->second != hyps[j].id) {
        // a switch after the car went unmatched for longer than switch_gap_s (out of range, hidden):
        // CLEAR MOT counts it, but only an appearance model could have kept the id
        const double gap = t - last_match_t[g_id[i]];
        const bool left = left_view.count(g_id[i]) > 0;
        ++m.id_switches;
        m.id_switches_after_gap += gap > p.switch_gap_s;
        m.id_switches_in_view += !left;
        event("id_switch", g_id[i], hyps[j].id, g[i].norm(), g_ret[i], (g[i] - h[j]).norm(), gap, left);
      }
    }
    for (const auto& [i, j] : matched) {
      left_view.erase(g_id[i]);
      last_match[g_id[i]] = hyps[j].id;
      last_match_t[g_id[i]] = t;
      dist_sum += (g[i] - h[j]).norm();
      moving_matches += hyps[j].moving;
      m.tracked_s += dt;
      if (hyps[j].age_s >= p.speed_after_s) speed_err.push_back(std::abs(hv[j].norm() - gv[i].norm()));
    }
    m.matches += matched.size();
    m.misses += g.size() - matched.size();
    // tracks on don't-care cars are neither matches nor false positives
    const std::vector<char> dc_free(dc.size(), 1);
    for (const auto& [i, j] : assign(dc, h, dc_free, h_free, p.match_distance_m)) h_free[j] = 0, ++m.dont_care_matches;
    auto nearest = [](const Eigen::Vector2d& q, const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b) {
      double d = -1;
      for (const auto* v : {&a, &b}) {
        for (const auto& x : *v) d = (d < 0 || (x - q).norm() < d) ? (x - q).norm() : d;
      }
      return d;
    };
    if (p.keep_events) {
      for (size_t i = 0; i < g.size(); ++i) {
        if (g_free[i]) event("miss", g_id[i], -1, g[i].norm(), g_ret[i], nearest(g[i], h, {}));
      }
    }
    for (size_t j = 0; j < h.size(); ++j) {
      if (h_free[j] && hyps[j].moving && h[j].norm() <= p.max_range_m) {
        ++m.false_positives;
        event("false_positive", -1, hyps[j].id, h[j].norm(), -1, nearest(h[j], g, dc));
      }
    }
  }
  m.mota = m.gt ? 1.0 - double(m.misses + m.false_positives + m.id_switches) / m.gt : 0.0;
  m.motp_m = m.matches ? dist_sum / m.matches : 0.0;
  m.speed_samples = speed_err.size();
  if (!speed_err.empty()) {
    double s = 0;
    for (double e : speed_err) s += e;
    m.speed_error_mean_mps = s / speed_err.size();
    std::sort(speed_err.begin(), speed_err.end());
    m.speed_error_p95_mps = speed_err[std::min(speed_err.size() - 1, speed_err.size() * 95 / 100)];
  }
  m.id_switches_per_100s = m.tracked_s > 0 ? 100.0 * m.id_switches / m.tracked_s : 0.0;
  m.id_switches_in_view_per_100s = m.tracked_s > 0 ? 100.0 * m.id_switches_in_view / m.tracked_s : 0.0;
  m.moving_label_fraction = m.matches ? double(moving_matches) / m.matches : 0.0;
  m.gt_cars_seen = seen.size();
  return m;
}

GhostCount countGhostsAmong(const std::string& gt_objects_json, const std::string& gt_trajectory_tum,
                            const std::string& run_trajectory_tum, const std::vector<Eigen::Vector3f>& points_map,
                            double margin_m, double max_range_m, bool seen_only) {
  std::ifstream fo(gt_objects_json);
  if (!fo) throw std::runtime_error("cannot read '" + gt_objects_json + "'");
  const auto j = nlohmann::json::parse(fo, nullptr, false);
  if (j.is_discarded() || !j.contains("moving_cars")) throw std::runtime_error("'" + gt_objects_json + "' is no gt_objects.json");
  const auto gt = datasets::readTum(gt_trajectory_tum);
  const auto est = datasets::readTum(run_trajectory_tum);
  if (est.poses.empty()) throw std::runtime_error("'" + run_trajectory_tum + "' holds no pose");
  Eigen::Isometry3d T_world_lidar;
  if (!poseAt(gt, est.stamps_s[0], T_world_lidar)) throw std::runtime_error("the GT trajectory does not cover the run's first pose");
  // swept boxes in the map frame on a 1 m grid for a quick lookup
  struct SweptBox {
    double x, y, z0, z1, c, s, hl, hw;
  };
  std::map<std::pair<long, long>, std::vector<SweptBox>> grid;
  for (const auto& c : j["moving_cars"]) {
    const double hl = 0.5 * c["length_m"].get<double>() + margin_m, hw = 0.5 * c["width_m"].get<double>() + margin_m;
    const double h = c["height_m"].get<double>();
    for (const auto& q : c["track"]) {
      if (seen_only && q.size() > 5 && q[5].get<int>() <= 0) continue;  // no return: it left nothing then
      // the car's points at time t entered the map through the run's pose of that time, so its box is
      // carried into the map by T_map_world(t) = T_map_lidar(t) * T_world_lidar_gt(t)^-1: drift then
      // moves the ghosts and the box together (times outside the run take its nearest end)
      if (max_range_m > 0) {
        Eigen::Isometry3d T_world_lidar_t;
        if (!poseAt(gt, q[0].get<double>(), T_world_lidar_t)) continue;
        const Eigen::Vector3d pl = T_world_lidar_t.inverse() * Eigen::Vector3d(q[1].get<double>(), q[2].get<double>(), 0);
        if (pl.head<2>().norm() > max_range_m) continue;
      }
      const Eigen::Isometry3d T_map_world = mapFromWorld(gt, est, q[0].get<double>());
      const Eigen::Vector3d centre = T_map_world * Eigen::Vector3d(q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
      const Eigen::Vector3d axis = T_map_world.linear() * Eigen::Vector3d(std::cos(q[4].get<double>()), std::sin(q[4].get<double>()), 0);
      const double yaw = std::atan2(axis.y(), axis.x());
      const SweptBox b{centre.x(), centre.y(), centre.z() + margin_m, centre.z() + h, std::cos(yaw), std::sin(yaw), hl, hw};
      const double r = std::hypot(hl, hw);
      for (long gx = static_cast<long>(std::floor(b.x - r)); gx <= static_cast<long>(std::floor(b.x + r)); ++gx) {
        for (long gy = static_cast<long>(std::floor(b.y - r)); gy <= static_cast<long>(std::floor(b.y + r)); ++gy) grid[{gx, gy}].push_back(b);
      }
    }
  }
  GhostCount out;
  out.map_points = points_map.size();
  for (const auto& p : points_map) {
    const Eigen::Vector3d m = p.cast<double>();
    const auto it = grid.find({static_cast<long>(std::floor(m.x())), static_cast<long>(std::floor(m.y()))});
    if (it == grid.end()) continue;
    for (const SweptBox& b : it->second) {
      const double dx = m.x() - b.x, dy = m.y() - b.y;
      if (std::abs(b.c * dx + b.s * dy) <= b.hl && std::abs(-b.s * dx + b.c * dy) <= b.hw && m.z() >= b.z0 && m.z() <= b.z1) {
        ++out.ghost_points;
        break;
      }
    }
  }
  return out;
}

GhostCount countGhostPoints(const std::string& gt_objects_json, const std::string& gt_trajectory_tum,
                            const std::string& run_trajectory_tum, const std::string& map_ply, double margin_m,
                            double max_range_m, bool seen_only) {
  // the map's points (binary little-endian float xyz, as roadslam-map writes map.ply)
  std::ifstream fp(map_ply, std::ios::binary);
  if (!fp) throw std::runtime_error("cannot read '" + map_ply + "'");
  std::string line;
  size_t n = 0;
  while (std::getline(fp, line) && line != "end_header") {
    if (line.rfind("element vertex ", 0) == 0) n = std::stoul(line.substr(15));
  }
  std::vector<float> xyz(3 * n);
  fp.read(reinterpret_cast<char*>(xyz.data()), static_cast<std::streamsize>(xyz.size() * sizeof(float)));
  if (static_cast<size_t>(fp.gcount()) != xyz.size() * sizeof(float)) throw std::runtime_error("'" + map_ply + "' is truncated");
  std::vector<Eigen::Vector3f> pts(n);
  for (size_t i = 0; i < n; ++i) pts[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
  return countGhostsAmong(gt_objects_json, gt_trajectory_tum, run_trajectory_tum, pts, margin_m, max_range_m, seen_only);
}

nlohmann::json toJson(const MotMetrics& m) {
  return {{"frames", m.frames}, {"gt", m.gt}, {"matches", m.matches}, {"misses", m.misses},
          {"false_positives", m.false_positives}, {"id_switches", m.id_switches}, {"mota", m.mota},
          {"motp_m", m.motp_m}, {"speed_samples", m.speed_samples}, {"speed_error_mean_mps", m.speed_error_mean_mps},
          {"speed_error_p95_mps", m.speed_error_p95_mps}, {"tracked_s", m.tracked_s},
          {"id_switches_per_100s", m.id_switches_per_100s}, {"moving_label_fraction", m.moving_label_fraction},
          {"gt_cars_seen", m.gt_cars_seen}, {"dont_care", m.dont_care}, {"dont_care_matches", m.dont_care_matches},
          {"id_switches_after_gap", m.id_switches_after_gap}, {"id_switches_in_view", m.id_switches_in_view},
          {"id_switches_in_view_per_100s", m.id_switches_in_view_per_100s}};
}

std::string toText(const MotMetrics& m) {
  char buf[1024];
  std::snprintf(buf, sizeof(buf),
                "frames              %zu\nGT objects          %zu (%zu cars)\nmatches             %zu\n"
                "misses              %zu\nfalse positives     %zu\nid switches         %zu (%.2f per 100 tracked s; %zu after a gap)\n"
                "  in view           %zu (%.2f per 100 tracked s; the car never left the sensor's view: KITTI's convention)\n"
                "MOTA                %.3f\nMOTP                %.3f m\nspeed error         %.2f m/s mean, %.2f m/s p95 (%zu samples)\n"
                "labelled moving     %.1f %% of matches\n"
                "don't care          %zu car-frames (hidden or far), %zu tracks on them\n",
                m.frames, m.gt, m.gt_cars_seen, m.matches, m.misses, m.false_positives, m.id_switches,
                m.id_switches_per_100s, m.id_switches_after_gap, m.id_switches_in_view, m.id_switches_in_view_per_100s, m.mota, m.motp_m, m.speed_error_mean_mps, m.speed_error_p95_mps,
                m.speed_samples, 100 * m.moving_label_fraction, m.dont_care, m.dont_care_matches);
  return buf;
}

std::string eventsCsv(const MotMetrics& m) {
  std::string out = "t,kind,gt_id,track_id,range_m,returns,nearest_m,gap_s,left_view\n";
  char buf[256];
  for (const MotEvent& e : m.events) {
    std::snprintf(buf, sizeof(buf), "%.6f,%s,%d,%d,%.2f,%d,%.2f,%.2f,%d\n", e.t, e.kind.c_str(), e.gt_id, e.track_id, e.range_m,
                  e.returns, e.nearest_m, e.gap_s, e.left_view);
    out += buf;
  }
  return out;
}

}  // namespace roadslam::eval
