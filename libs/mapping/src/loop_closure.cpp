#include "roadslam/mapping/loop_closure.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "ini_keys.h"
#include "roadslam/registration/registration.h"

namespace roadslam::mapping {
namespace {

double angleOf(const Eigen::Isometry3d& T) { return Eigen::AngleAxisd(T.rotation()).angle(); }

/// Points of keyframes [first, last] mapped into keyframe \p frame's lidar frame by the graph estimate.
registration::PointCloud submap(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, size_t first,
                                size_t last, size_t frame, double voxel_m) {
  registration::PointCloud pts;
  const Eigen::Isometry3d T_frame_map = T_map_kf[frame].inverse();
  for (size_t i = first; i <= last; ++i) {
    const Eigen::Isometry3d T = T_frame_map * T_map_kf[i];
    for (const auto& q : kfs[i].points_lidar) pts.push_back(T * q.cast<double>());
  }
  return registration::voxelDownsample(pts, voxel_m);
}

const NameTable<LoopCandidates>& candidateNames() {
  static const NameTable<LoopCandidates> t{
      {LoopCandidates::Radius, "radius"}, {LoopCandidates::ScanContext, "scan_context"}, {LoopCandidates::Both, "both"}};
  return t;
}

registration::PointCloud pointsOf(const Keyframe& kf) {
  registration::PointCloud pts;
  pts.reserve(kf.points_lidar.size());
  for (const auto& q : kf.points_lidar) pts.push_back(q.cast<double>());
  return pts;
}

}  // namespace

LoopClosureParams::LoopClosureParams() {
  coarse.method = registration::Method::Ndt;
  coarse.ndt_resolution_m = 2.0;
  coarse.ndt_levels = 3;
  coarse.max_iterations = 40;
  coarse.max_correction_m = 15.0;
  fine.method = registration::Method::IcpPointToPlane;
  fine.max_correspondence_distance_m = 1.0;
  fine.max_iterations = 40;
  fine.max_correction_m = 3.0;
}

void LoopClosureParams::fields(ParamTable& t) {
  t.flag("enabled", enabled);
  t.num("search_radius_m", search_radius_m);
  t.num("search_height_m", search_height_m);
  t.flag("level_guess", level_guess);
  t.num("min_travel_m", min_travel_m);
  t.num("check_every_m", check_every_m);
  t.num("max_candidates", max_candidates);
  t.num("query_keyframes", query_keyframes);
  t.num("target_half_width", target_half_width);
  t.num("source_voxel_m", source_voxel_m);
  t.num("target_voxel_m", target_voxel_m);
  t.num("max_fitness_m", max_fitness_m);
  t.num("min_overlap", min_overlap);
  t.num("consistency_abs_m", consistency_abs_m);
  t.num("consistency_ratio", consistency_ratio);
  t.angle("consistency_rot_deg", consistency_rot_rad);
  t.scaled("consistency_rot_deg_per_100m", consistency_rot_rad_per_m, unit::kDeg / 100);  // [deg/100 m] in the ini
  t.num("max_loop_residual_m", max_loop_residual_m);
  t.num("information_scale", information_scale);
  t.num("skip_after_loop_m", skip_after_loop_m);
  t.choice("candidates", candidates, candidateNames());
  t.num("place_consistency_abs_m", place_consistency_abs_m);
  t.num("place_consistency_ratio", place_consistency_ratio);
  t.angle("place_consistency_rot_deg", place_consistency_rot_rad);
  t.scaled("place_consistency_rot_deg_per_100m", place_consistency_rot_rad_per_m, unit::kDeg / 100);
  t.num("place_information_scale", place_information_scale);
}

void LoopClosureParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<LoopClosureParams>());
  if (search_radius_m <= 0 || check_every_m <= 0 || max_candidates < 1 || query_keyframes < 1 ||
      target_half_width < 0 || source_voxel_m <= 0 || target_voxel_m <= 0 || information_scale <= 0) {
    throw std::runtime_error("[" + s + "]: search_radius_m, check_every_m, max_candidates, query_keyframes, "
                             "*_voxel_m and information_scale must be > 0");
  }
  coarse.loadFromConfigFile(cfg, s + "_coarse");
  fine.loadFromConfigFile(cfg, s + "_fine");
  place.loadFromConfigFile(cfg, s + "_place");
  global.loadFromConfigFile(cfg, s + "_global");
}

void LoopClosureParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
  coarse.saveToConfigFile(cfg, s + "_coarse");
  fine.saveToConfigFile(cfg, s + "_fine");
  place.saveToConfigFile(cfg, s + "_place");
  global.saveToConfigFile(cfg, s + "_global");
}

std::vector<size_t> findLoopCandidates(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, size_t query,
                                       const LoopClosureParams& p) {
  std::vector<std::pair<double, size_t>> near;
  const Eigen::Vector3d q = T_map_kf[query].translation();
  for (size_t j = 0; j < query; ++j) {
    if (kfs[query].path_m - kfs[j].path_m < p.min_travel_m) break;  // path grows with j
    const Eigen::Vector3d dq = T_map_kf[j].translation() - q;
    const double d = dq.head<2>().norm();
    if (d < p.search_radius_m && std::abs(dq.z()) < p.search_height_m) near.emplace_back(d, j);
  }
  std::sort(near.begin(), near.end());
  std::vector<size_t> out;
  // one candidate per stretch of road: skip candidates next to an already chosen one
  for (const auto& [d, j] : near) {
    bool close = false;
    for (size_t o : out) close |= std::abs(kfs[o].path_m - kfs[j].path_m) < 2 * p.search_radius_m;
    if (!close) out.push_back(j);
    if (out.size() >= static_cast<size_t>(p.max_candidates)) break;
  }
  return out;
}

namespace {

/// What a loop's correction of the graph's guess may be, and the weight of its edge.
struct Acceptance {
  double abs_m, ratio, rot_rad, rot_rad_per_m;  ///< correction <= abs + ratio * path (rotation alike)
  double information_scale;                     ///< multiplies the fine ICP information [-]
};

/// Steps 2-3 of loop_closure.h from \p start (T_match_query): the coarse registration when \p coarse, the
/// fine ICP of the query submap against the candidate's, its fitness and overlap tests and the correction's
/// bounds. \p t0: when the verification began (LoopResult::ms).
LoopResult verifySubmaps(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, size_t query, size_t match,
                         const LoopClosureParams& p, const Eigen::Isometry3d& start, bool coarse, const Acceptance& a,
                         std::chrono::steady_clock::time_point t0) {
  LoopResult r;
  r.query = query;
  r.match = match;
  const size_t qfirst = query + 1 >= static_cast<size_t>(p.query_keyframes) ? query + 1 - p.query_keyframes : 0;
  const size_t tfirst = match >= static_cast<size_t>(p.target_half_width) ? match - p.target_half_width : 0;
  const size_t tlast = std::min(match + p.target_half_width, qfirst > 0 ? qfirst - 1 : 0);
  const auto source = submap(kfs, T_map_kf, qfirst, query, query, p.source_voxel_m);
  const auto target_pts = submap(kfs, T_map_kf, tfirst, std::max(tlast, match), match, p.target_voxel_m);
  const Eigen::Isometry3d guess = T_map_kf[match].inverse() * T_map_kf[query];
  auto finish = [&](const std::string& why) {
    r.reason = why;
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  Eigen::Isometry3d fine_start = start;
  if (coarse) {
    const registration::Target coarse_target(target_pts, p.coarse);
    const auto c = registration::align(coarse_target, source, start, p.coarse);
    if (!c.converged) return finish("coarse: " + registration::toString(c.status));
    fine_start = c.T_target_source;
  }
  const registration::Target fine_target(target_pts, p.fine);
  const auto f = registration::align(fine_target, source, fine_start, p.fine);
  r.T_match_query = f.T_target_source;
  r.fitness_m = f.fitness;
  r.overlap = source.empty() ? 0.0 : static_cast<double>(f.inliers) / source.size();
  // the fine ICP's information is about the match frame (left perturbations); the loop edge's residual
  // is in the query's frame
  r.information = a.information_scale * sourceFrameInformation(f.information, f.T_target_source);
  const Eigen::Isometry3d corr = guess.inverse() * f.T_target_source;
  r.correction_m = corr.translation().norm();
  r.correction_rad = angleOf(corr);
  if (!f.converged) return finish("fine: " + registration::toString(f.status));
  if (r.fitness_m > p.max_fitness_m) return finish("fitness");
  if (r.overlap < p.min_overlap) return finish("overlap");
  const double path = kfs[query].path_m - kfs[match].path_m;
  if (r.correction_m > a.abs_m + a.ratio * path || r.correction_rad > a.rot_rad + a.rot_rad_per_m * path) {
    return finish("inconsistent with odometry");
  }
  r.accepted = true;
  return finish("accepted");
}

}  // namespace

LoopResult verifyLoop(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, size_t query, size_t match,
                      const LoopClosureParams& p) {
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::Isometry3d start = T_map_kf[match].inverse() * T_map_kf[query];
  // a revisit is on the same road: the odometry's vertical drift (its largest) is not a guess
  if (p.level_guess) start.translation().z() = 0;
  return verifySubmaps(kfs, T_map_kf, query, match, p, start, true,
                       {p.consistency_abs_m, p.consistency_ratio, p.consistency_rot_rad, p.consistency_rot_rad_per_m,
                        p.information_scale},
                       t0);
}

std::vector<size_t> findPlaceCandidates(const place::ScanContextDatabase& db, const std::vector<Keyframe>& kfs,
                                        size_t query, const LoopClosureParams& p) {
  std::vector<size_t> out;
  for (const auto& m : db.query(kfs[query].descriptor, kfs[query].path_m, p.max_candidates)) out.push_back(m.id);
  return out;
}

const registration::FeatureCloud& KeyframeFeatures::of(const std::vector<Keyframe>& kfs, size_t i,
                                                       const registration::GlobalParams& p) {
  if (f_.size() <= i) f_.resize(i + 1);
  if (!f_[i]) {
    f_[i] = std::make_unique<registration::FeatureCloud>(registration::computeFeatures(pointsOf(kfs.at(i)), p));
    ++computed_;
  }
  return *f_[i];
}

void KeyframeFeatures::invalidate(size_t i) {
  if (i < f_.size()) f_[i].reset();
}

LoopResult verifyPlaceLoop(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, size_t query, size_t match,
                           const LoopClosureParams& p, KeyframeFeatures& features) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto g = registration::alignGlobal(features.of(kfs, match, p.global), features.of(kfs, query, p.global), p.global);
  if (!g.converged) {
    LoopResult r;
    r.query = query;
    r.match = match;
    r.reason = "global: " + registration::toString(g.status);
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }
  return verifySubmaps(kfs, T_map_kf, query, match, p, g.T_target_source, false,
                       {p.place_consistency_abs_m, p.place_consistency_ratio, p.place_consistency_rot_rad,
                        p.place_consistency_rot_rad_per_m, p.place_information_scale},
                       t0);
}

}  // namespace roadslam::mapping
