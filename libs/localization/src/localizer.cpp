#include "roadslam/localization/localizer.h"

#include <optional>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

#include "roadslam/mapping/loop_closure.h"
#include "roadslam/place/scan_context.h"

namespace roadslam::localization {

LocalizerParams::LocalizerParams() {
  track.method = registration::Method::IcpPointToPlane;
  track.max_correspondence_distance_m = 1.0;
  track.max_iterations = 30;
  track.max_correction_m = 3.0;
}

void LocalizerParams::fields(ParamTable& t) {
  t.num("map_voxel_m", map_voxel_m);
  t.num("sweep_voxel_m", sweep_voxel_m);
  t.num("min_overlap", min_overlap);
  t.num("relocalize_candidates", relocalize_candidates);
  t.num("relocalize_max_distance", relocalize_max_distance);
}

void LocalizerParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<LocalizerParams>());
  if (map_voxel_m <= 0 || sweep_voxel_m <= 0 || relocalize_candidates < 1 || relocalize_max_distance <= 0) {
    throw std::runtime_error("[" + s + "]: *_voxel_m, relocalize_candidates and relocalize_max_distance must be > 0");
  }
  track.loadFromConfigFile(cfg, s + "_track");
}

void LocalizerParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
  track.saveToConfigFile(cfg, s + "_track");
}

std::string toString(LocalizationStatus s) {
  switch (s) {
    case LocalizationStatus::Tracked: return "tracked";
    case LocalizationStatus::Relocalized: return "relocalized";
    case LocalizationStatus::Lost: return "lost";
  }
  return "unknown";
}

struct Localizer::Impl {
  mapping::MapFolder map;
  LocalizerParams p;
  std::unique_ptr<registration::Target> target;
  place::ScanContextDatabase places;
  mutable mapping::KeyframeFeatures features;  ///< map keyframes' global-registration features, on first use
  std::optional<Eigen::Isometry3d> last, before_last;  ///< T_map_lidar of the last two localized sweeps
  size_t map_points = 0;
};

Localizer::Localizer(mapping::MapFolder map, LocalizerParams p) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.p = std::move(p);
  m.map = std::move(map);
  registration::PointCloud pts;
  for (size_t i = 0; i < m.map.keyframes.size(); ++i)
    for (const auto& q : m.map.keyframes[i].points_lidar) pts.push_back(m.map.T_map_kf[i] * q.cast<double>());
  const auto map_pts = registration::voxelDownsample(pts, m.p.map_voxel_m);
  m.map_points = map_pts.size();
  m.target = std::make_unique<registration::Target>(map_pts, m.p.track);
  place::ScanContextParams sp = m.map.scan_context;
  sp.min_travel_m = 0;  // every map keyframe is a candidate
  sp.max_distance = m.p.relocalize_max_distance;
  m.places = place::ScanContextDatabase(sp);
  for (size_t i = 0; i < m.map.keyframes.size(); ++i) m.places.add(i, 0.0, m.map.keyframes[i].descriptor);
}

Localizer::~Localizer() = default;
size_t Localizer::mapPoints() const { return impl_->map_points; }
void Localizer::reset() { impl_->last.reset(), impl_->before_last.reset(); }

LocalizationResult Localizer::track(const registration::PointCloud& src, const Eigen::Isometry3d& guess) const {
  const Impl& m = *impl_;
  LocalizationResult out;
  const auto r = registration::align(*m.target, src, guess, m.p.track);
  out.confidence = src.empty() ? 0.0 : static_cast<double>(r.inliers) / src.size();
  out.T_map_lidar = r.T_target_source;
  out.weak_directions = r.degeneracy.num_weak;
  if (!r.converged) {
    out.reason = "tracking: " + registration::toString(r.status);
  } else if (out.confidence < m.p.min_overlap) {
    out.reason = "tracking: overlap " + std::to_string(out.confidence);
  } else {
    out.status = LocalizationStatus::Tracked;
  }
  return out;
}

LocalizationResult Localizer::relocalize(const std::vector<Eigen::Vector3d>& points_lidar,
                                         const registration::PointCloud& src) const {
  const Impl& m = *impl_;
  LocalizationResult best;
  best.reason = "relocalization: no place matched";
  const auto sc = place::makeScanContext(points_lidar, m.places.params());
  const auto sweep = registration::computeFeatures(points_lidar, m.p.global, false);
  for (const auto& c : m.places.query(sc, 0.0, m.p.relocalize_candidates)) {
    const auto g = registration::alignGlobal(m.features.of(m.map.keyframes, c.id, m.p.global), sweep, m.p.global);
    if (!g.converged) {
      best.reason = "relocalization: global " + registration::toString(g.status);
      continue;
    }
    LocalizationResult t = track(src, m.map.T_map_kf[c.id] * g.T_target_source);
    if (t.status == LocalizationStatus::Tracked) {
      t.status = LocalizationStatus::Relocalized;
      t.keyframe = c.id;
      return t;
    }
    best.reason = "relocalization: " + t.reason;
  }
  return best;
}

LocalizationResult Localizer::localize(const std::vector<Eigen::Vector3d>& points_lidar) {
  Impl& m = *impl_;
  const auto src = registration::voxelDownsample(points_lidar, m.p.sweep_voxel_m);
  LocalizationResult r;
  if (m.last) {
    // constant velocity: the last motion applied again
    const Eigen::Isometry3d guess = m.before_last ? *m.last * (m.before_last->inverse() * *m.last) : *m.last;
    r = track(src, guess);
  }
  if (r.status != LocalizationStatus::Tracked) {
    const std::string why = r.reason;
    r = relocalize(points_lidar, src);
    if (r.status == LocalizationStatus::Lost && !why.empty()) r.reason = why + "; " + r.reason;
  }
  if (r.status == LocalizationStatus::Lost) {
    reset();
  } else {
    // keep the rotation orthonormal: the prediction multiplies the last poses, rounding errors would grow
    r.T_map_lidar.linear() = Eigen::Quaterniond(r.T_map_lidar.linear()).normalized().toRotationMatrix();
    // a relocalization starts the motion model afresh (the previous pose may be from before a jump)
    if (r.status == LocalizationStatus::Relocalized) m.before_last.reset();
    else m.before_last = m.last;
    m.last = r.T_map_lidar;
  }
  return r;
}

}  // namespace roadslam::localization
