#include "roadslam/objects/tracker.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "wrap_pi.h"

namespace roadslam::objects {
namespace {

using detail::wrapPi;

constexpr double kUnassignable = 1e9;  // cost of a gated-out pair in the assignment
constexpr double kFaceMaxObliquity = 0.766;  // cos 40 deg: a car's front or rear seen roughly head-on

/// A detection in the map frame: its box and the box's corners (x-y).
struct Detection {
  OrientedBox box;
  std::array<Eigen::Vector2d, 4> corners;
  double dt = 0;  // its points' time minus the sweep's reference time [s]
  double top = 0;  // highest point above the local ground [m]
  int free_through = 0, free_hit = 0;  // Object's
};

constexpr double kHeadingGate_rad = 30.0 * M_PI / 180.0;  // a box axis this close to the velocity is its heading
constexpr int kReidMinMisses = 2;  // sweeps a track must have lost its object to hand its id on (Tracker::reidentify)
constexpr size_t kHistoryMax = 100;  // 10 s of detections at 10 Hz before a track is labelled moving
constexpr double kFreeDecay = 0.8;    // weight of a detection's free-space evidence per detection back
constexpr double kFreeMinEvidence = 10;  // points with evidence below which the moving label ignores it

void remember(Track& tr, const Detection& d, double t) {
  if (tr.moving_since >= 0 || tr.history->size() >= kHistoryMax) return;
  tr.history->push_back({t, d.box});
}

Detection toMap(const Object& o, const Eigen::Isometry3d& T_map_lidar) {
  Detection d;
  const OrientedBox& b = o.box;
  const std::array<Eigen::Vector2d, 4> lidar = b.corners();
  for (size_t k = 0; k < 4; ++k) d.corners[k] = (T_map_lidar * Eigen::Vector3d(lidar[k].x(), lidar[k].y(), 0)).head<2>();
  d.box.centre_m = (T_map_lidar * Eigen::Vector3d(b.centre_m.x(), b.centre_m.y(), 0)).head<2>();
  const Eigen::Vector3d um = T_map_lidar.linear() * Eigen::Vector3d(std::cos(b.yaw_rad), std::sin(b.yaw_rad), 0);
  d.box.yaw_rad = std::atan2(um.y(), um.x());
  d.box.length_m = b.length_m, d.box.width_m = b.width_m;
  d.top = o.top_height_m;
  d.free_through = o.free_through, d.free_hit = o.free_hit;
  d.dt = std::isfinite(o.dt_s) && std::abs(o.dt_s) < 0.5 ? o.dt_s : 0.0;
  const double z0 = T_map_lidar.translation().z();
  d.box.z_min_m = b.z_min_m + z0, d.box.z_max_m = b.z_max_m + z0;
  return d;
}

/// The detection's extents along the heading \p h and across it, and its centre completed to the
/// track's remembered extents \p L x \p W away from the sensor at \p s: the faces seen are the near ones.
struct Completed {
  Eigen::Vector2d centre;
  double along = 0, across = 0;
};

Completed complete(const Detection& d, double h, double L, double W, const Eigen::Vector2d& s) {
  const Eigen::Vector2d u(std::cos(h), std::sin(h)), v(-u.y(), u.x());
  double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
  for (const auto& c : d.corners) {
    lo_u = std::min(lo_u, c.dot(u)), hi_u = std::max(hi_u, c.dot(u));
    lo_v = std::min(lo_v, c.dot(v)), hi_v = std::max(hi_v, c.dot(v));
  }
  auto centreOn = [](double lo, double hi, double full, double sensor) {
    if (hi - lo >= full) return 0.5 * (lo + hi);
    return std::abs(sensor - lo) < std::abs(sensor - hi) ? lo + 0.5 * full : hi - 0.5 * full;
  };
  Completed c;
  // the extents are the box's own, paired with the heading's axes by its orientation: the projections
  // of a box turned off the heading (a car in a turn, its velocity lagging) overstate both
  const bool aligned = std::abs(std::cos(d.box.yaw_rad - h)) >= std::sqrt(0.5);
  c.along = aligned ? d.box.length_m : d.box.width_m, c.across = aligned ? d.box.width_m : d.box.length_m;
  c.centre = centreOn(lo_u, hi_u, L, s.dot(u)) * u + centreOn(lo_v, hi_v, W, s.dot(v)) * v;
  return c;
}

/// The car-size prior on a detection with no known heading: one face (a box car_face_min_m..
/// car_face_max_m long, at most car_face_max_depth_m wide, facing the sensor within 40 deg) seen from
/// car_prior_min_range_m or farther is a car's front or rear; the car reaches car_length_m away from
/// the sensor along the face's normal (Zhang et al. 2017 fit the visible L; the hidden rest follows
/// from the size). \p centre: the detection's centre moved so; \p los_dir: the normal.
bool isCarFace(const Detection& d, const Eigen::Vector2d& s, const TrackerParams& p, Eigen::Vector2d* centre = nullptr,
               Eigen::Vector2d* los_dir = nullptr) {
  const OrientedBox& b = d.box;
  const Eigen::Vector2d los = b.centre_m - s;
  const double range = los.norm();
  if (p.car_length_m <= 0 || range < p.car_prior_min_range_m) return false;
  if (b.width_m > p.car_face_max_depth_m || b.length_m < p.car_face_min_m || b.length_m > p.car_face_max_m) return false;
  // the face's normal, away from the sensor, within 40 deg of the line of sight
  Eigen::Vector2d n(-std::sin(b.yaw_rad), std::cos(b.yaw_rad));
  if (n.dot(los) < 0) n = -n;
  if (n.dot(los) < kFaceMaxObliquity * range) return false;
  if (centre) *centre = b.centre_m + n * 0.5 * std::max(0.0, p.car_length_m - b.width_m);
  if (los_dir) *los_dir = n;
  return true;
}

/// A track that takes a car's face: its extent along the line of sight is a car's length (the extents
/// are along / across its heading; the face's direction is the heading of a track born on it).
void growToCarBehindFace(Track& tr, const Detection& d, const Eigen::Vector2d& s, const TrackerParams& p) {
  Eigen::Vector2d u;
  if (tr.moving || !isCarFace(d, s, p, nullptr, &u)) return;
  const Eigen::Vector2d h(std::cos(tr.heading), std::sin(tr.heading));
  if (std::abs(h.dot(u)) < 0.5) {
    tr.width = std::max(tr.width, p.car_length_m);  // the line of sight runs across the heading
  } else {
    tr.length = std::max(tr.length, p.car_length_m);
  }
}

/// The detection completed for \p tr: with a heading from its velocity (moving) and car-sized, to at
/// least the car size; otherwise to the extents the track has seen (capped), and a single face with
/// no heading known to a car behind it (isCarFace).
Completed completeFor(const Track& tr, const Detection& d, const Eigen::Vector2d& s, const TrackerParams& p_) {
  double L = std::min(tr.length, p_.max_extent_growth_m), W = std::min(tr.width, p_.max_extent_growth_m);
  if (tr.moving) {
    L = std::max(L, p_.car_length_m), W = std::max(W, p_.car_width_m);
    return complete(d, tr.heading, L, W, s);
  }
  Completed c = complete(d, tr.heading, L, W, s);
  Eigen::Vector2d face_centre;
  if (L < p_.car_face_max_m && isCarFace(d, s, p_, &face_centre)) c.centre = face_centre;  // never seen longer than a face
  return c;
}

}  // namespace

void Tracker::predict(double t) {
  const double dt = std::max(0.0, t - t_);
  for (Track& tr : tracks_) tr.filter->predict(dt, tr.moving, tr.x, tr.P);
  t_ = t;
}

void Tracker::endAll(double t, const std::string& reason) {
  for (Track& tr : tracks_) ended_.push_back({tr, reason, t});
  tracks_.clear();
}

void Tracker::prune(double t, const std::string& reason) {
  std::vector<Track> keep;
  for (Track& tr : tracks_) {
    const bool dead = tr.state == TrackState::Tentative ? tr.misses > p_.tentative_max_misses : tr.misses > p_.max_misses;
    if (dead || !tr.x.allFinite()) {
      ended_.push_back({tr, tr.x.allFinite() ? reason : "diverged", t});
    } else {
      keep.push_back(std::move(tr));
    }
  }
  tracks_ = std::move(keep);
}

void Tracker::coast(double t, const std::string& reason) {
  if (!std::isfinite(t)) return;
  if (!started_) started_ = true, t_ = t;
  if (t - t_ > p_.max_dt_s || t < t_) endAll(t, "gap");
  predict(t);
  for (Track& tr : tracks_) ++tr.misses, tr.last_detection = -1;
  prune(t, reason);
}

namespace {

/// Gated association costs of \p tracks against \p dets (x-y distance of the completed detection centre
/// to the track's prediction at the detection's time, plus the extent growth); \p comp: the completions.
std::vector<std::vector<double>> associationCosts(const std::vector<Track>& tracks, const std::vector<Detection>& dets,
                                                  const Eigen::Vector2d& s, const TrackerParams& p,
                                                  std::vector<std::vector<Completed>>& comp) {
  std::vector<std::vector<double>> cost(tracks.size(), std::vector<double>(dets.size(), kUnassignable));
  comp.assign(tracks.size(), std::vector<Completed>(dets.size()));
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * p.meas_sigma_m * p.meas_sigma_m;
  for (size_t i = 0; i < tracks.size(); ++i) {
    const Track& tr = tracks[i];
    const Eigen::Matrix2d S_inv = (tr.P.topLeftCorner<2, 2>() + R).inverse();  // innovation covariance
    for (size_t j = 0; j < dets.size(); ++j) {
      // completion moves a centre by at most half the capped extents: farther boxes cannot be in the gate
      if ((dets[j].box.centre_m - tr.x.head<2>()).norm() > p.gate_m + p.max_extent_growth_m) continue;
      comp[i][j] = completeFor(tr, dets[j], s, p);
      const Eigen::Vector2d r = comp[i][j].centre - (tr.x.head<2>() + dets[j].dt * tr.x.tail<2>());
      const double d = r.norm(), m2 = r.dot(S_inv * r);
      if (d > p.gate_m || m2 > p.gate_sigma * p.gate_sigma) continue;
      // extents seen now against the track's (capped: a car seen whole once is a car seen in part now)
      const double dl = std::max(0.0, comp[i][j].along - std::min(tr.length, p.max_extent_growth_m)) +
                        std::max(0.0, comp[i][j].across - std::min(tr.width, p.max_extent_growth_m));
      cost[i][j] = d + p.size_weight * dl;
    }
  }
  return cost;
}

/// The static / moving label of a confirmed track (TrackerParams::moving_*), with hysteresis: it
/// stops moving below half the speed; a track never seen car-sized is never moving.
void label(Track& tr, double t, const TrackerParams& p) {
  if (tr.state != TrackState::Confirmed) return;
  const double v = tr.speed(), travel = (tr.x.head<2>() - tr.birth_xy).norm();
  const double lo = std::min(tr.length, tr.width), hi = std::max(tr.length, tr.width);
  const bool car_sized = hi <= p.moving_max_length_m && lo <= p.moving_max_width_m && lo >= p.moving_min_width_m &&
                         tr.top_height <= p.moving_max_height_m;
  // static by its points: they lie where the rays of a second before ended (free_space.h)
  const double evidence = tr.free_through + tr.free_hit;
  const bool seen_static = p.moving_min_free_fraction > 0 && evidence >= kFreeMinEvidence &&
                           tr.free_through < p.moving_min_free_fraction * evidence;
  if (v > p.moving_speed_mps && travel > p.moving_min_travel_m && tr.hits >= p.moving_min_hits && car_sized &&
      (tr.moving || !seen_static)) {
    if (tr.moving_since < 0) tr.moving_since = t;
    tr.moving = true;
  }
  if (v < 0.5 * p.moving_speed_mps || !car_sized) tr.moving = false;
  if (!tr.moving) return;
  // the heading follows the velocity; extents swap when it turns by more than 45 deg off them
  const double h = std::atan2(tr.x(3), tr.x(2));
  if (std::abs(std::sin(wrapPi(h - tr.heading))) > std::sqrt(0.5)) std::swap(tr.length, tr.width);
  tr.heading = h;
}

/// The box's axis nearest the moving track's velocity heading, as a heading measurement
/// (TrackerParams::heading_sigma_rad; the IMM takes it, MotionFilter::correctHeading): the L-shape's orientation turns with the car at once, while the
/// velocity from the centres lags a turn by 10-25 deg (the 30 s loop's car turning right 39 m away).
/// Axes farther than kHeadingGate_rad off are no measurement (a box of mixed faces).
void takeHeading(Track& tr, const Detection& d, const TrackerParams& p_) {
  if (p_.heading_sigma_rad <= 0 || !tr.moving) return;
  const double h = std::atan2(tr.x(3), tr.x(2));
  double best = 1e9;
  for (int k = 0; k < 4; ++k) {
    const double diff = std::remainder(d.box.yaw_rad + k * M_PI / 2 - h, 2 * M_PI);
    if (std::abs(diff) < std::abs(best)) best = diff;
  }
  if (std::abs(best) > kHeadingGate_rad) return;
  tr.filter->correctHeading(h + best, p_.heading_sigma_rad, tr.x, tr.P);
}

/// \p tr takes the detection \p d (index \p j) completed as \p c, seen from \p s at \p t.
void take(Track& tr, const Detection& d, const Completed& c, const Eigen::Vector2d& s, double t, int j, const TrackerParams& p_) {
  tr.filter->correct(c.centre, d.dt, Eigen::Matrix2d::Identity() * p_.meas_sigma_m * p_.meas_sigma_m, tr.x, tr.P);
  takeHeading(tr, d, p_);
  tr.length = std::max(tr.length, c.along);
  tr.width = std::max(tr.width, c.across);
  growToCarBehindFace(tr, d, s, p_);
  ++tr.hits, tr.misses = 0, tr.t_last = t, tr.last_detection = j;
  tr.free_through = kFreeDecay * tr.free_through + d.free_through;
  tr.free_hit = kFreeDecay * tr.free_hit + d.free_hit;
  tr.z_min = d.box.z_min_m, tr.z_max = d.box.z_max_m, tr.ground_z = d.box.z_max_m - d.top;
  remember(tr, d, t);
  tr.top_height = std::max(tr.top_height, d.top);
  if (tr.hits >= p_.confirm_hits) tr.state = TrackState::Confirmed;
  label(tr, t, p_);
}

/// A tentative track \p id born on the detection \p d (index \p j) seen from \p s at \p t, its filter
/// a copy of \p filter started there.
Track born(int id, const Detection& d, const Eigen::Vector2d& s, double t, int j, const TrackerParams& p_,
           const MotionFilter& filter) {
  const double m2 = p_.meas_sigma_m * p_.meas_sigma_m, v2 = p_.init_speed_sigma_mps * p_.init_speed_sigma_mps;
  Track tr;
  tr.id = id;
  tr.x << d.box.centre_m, 0, 0;
  tr.P = Eigen::Vector4d(m2, m2, v2, v2).asDiagonal();
  tr.heading = d.box.yaw_rad;
  const Completed c = complete(d, tr.heading, 0, 0, s);
  tr.length = c.along, tr.width = c.across;
  // a car's face: its centre is behind it, and it drives along the line of sight (the filter's heading)
  Eigen::Vector2d centre = d.box.centre_m, los;
  double heading = d.box.yaw_rad;
  if (isCarFace(d, s, p_, &centre, &los)) heading = std::atan2(los.y(), los.x());
  tr.x.head<2>() = centre;
  growToCarBehindFace(tr, d, s, p_);
  tr.filter = TrackFilter(filter.clone());
  tr.filter->start(heading, tr.x, tr.P);
  tr.z_min = d.box.z_min_m, tr.z_max = d.box.z_max_m, tr.top_height = d.top, tr.ground_z = d.box.z_max_m - d.top;
  tr.hits = 1, tr.t_birth = tr.t_last = t, tr.birth_xy = tr.x.head<2>(), tr.last_detection = j;
  tr.free_through = d.free_through, tr.free_hit = d.free_hit;
  remember(tr, d, t);
  if (tr.hits >= p_.confirm_hits) tr.state = TrackState::Confirmed;
  return tr;
}

}  // namespace

void Tracker::update(double t, const Eigen::Isometry3d& T_map_lidar, const std::vector<Object>& objects) {
  if (!std::isfinite(t) || !T_map_lidar.matrix().allFinite()) return coast(t, "pose");
  if (!started_) started_ = true, t_ = t;
  if (t - t_ > p_.max_dt_s || t < t_) endAll(t, "gap");
  predict(t);
  const Eigen::Vector2d s = T_map_lidar.translation().head<2>();
  std::vector<Detection> dets;
  dets.reserve(objects.size());
  for (const Object& o : objects) dets.push_back(toMap(o, T_map_lidar));  // finite: segmentObjects drops NaN points
  std::vector<std::vector<Completed>> comp;
  const auto cost = associationCosts(tracks_, dets, s, p_, comp);
  const std::vector<int> match = hungarian(cost);
  std::vector<char> taken(dets.size(), false);
  std::vector<int> confirmed_now;  // ids of the tracks this sweep confirmed
  for (size_t i = 0; i < tracks_.size(); ++i) {
    const int j = match[i];
    tracks_[i].last_detection = -1;
    if (j < 0 || cost[i][static_cast<size_t>(j)] >= kUnassignable) {
      ++tracks_[i].misses;
      continue;
    }
    taken[static_cast<size_t>(j)] = true;
    const bool was_tentative = tracks_[i].state == TrackState::Tentative;
    take(tracks_[i], dets[static_cast<size_t>(j)], comp[i][static_cast<size_t>(j)], s, t, j, p_);
    if (was_tentative && tracks_[i].state == TrackState::Confirmed) confirmed_now.push_back(tracks_[i].id);
  }
  prune(t, "missed");
  for (size_t j = 0; j < dets.size(); ++j) {
    if (!taken[j]) tracks_.push_back(born(next_id_++, dets[j], s, t, static_cast<int>(j), p_, *filter_));
  }
  for (int id : confirmed_now) reidentify(id);
}

void Tracker::reidentify(int young_id) {
  if (p_.reid_gate_m <= 0) return;
  auto young = std::find_if(tracks_.begin(), tracks_.end(), [&](const Track& tr) { return tr.id == young_id; });
  if (young == tracks_.end()) return;
  // A fast moving track that lost its object (missed this sweep and the last, still coasting) and is
  // predicted within reid_gate_m of a track its object's detections just confirmed: the object left
  // the gate (a turn the prediction lagged, a partial view completed on the wrong side) and came back
  // as a new track. Track-to-track association of the lost track with the new one, as the
  // re-identification step of ByteTrack / OC-SORT, by position only: the cars carry no appearance.
  // Only tracks labelled moving (a static track continued by clutter's new tracks was labelled moving
  // by the merges: hedges on the hard loop), faster than clutter's sliding boxes were when they lost them, and lost for two
  // sweeps (after one, a duplicate track had taken the detection: the lost one takes it back next).
  auto best = tracks_.end();
  double best_d = p_.reid_gate_m;
  for (auto it = tracks_.begin(); it != tracks_.end(); ++it) {
    if (it == young || !it->moving || it->last_detection >= 0 || it->misses < kReidMinMisses) continue;
    if (it->t_birth >= young->t_birth || it->speed() <= p_.reid_min_speed_mps) continue;
    const double d = (it->x.head<2>() - young->x.head<2>()).norm();
    if (d < best_d) best_d = d, best = it;
  }
  if (best == tracks_.end()) return;
  // The lost track takes the new one's position estimate as a measurement (its covariance as R): the
  // velocity of the longer history, corrected through its coasting covariance, beats that of 3 boxes
  // (a car sliding past an occluder's gap shows the same points for 3 sweeps). The jump is no turn:
  // the turn rate restarts. It keeps its label, extents and history (moving: no more records).
  Track merged = *best;
  merged.filter->correct(young->x.head<2>(), 0, young->P.topLeftCorner<2, 2>(), merged.x, merged.P);
  merged.filter->restartTurn(merged.x, merged.P);
  merged.misses = 0, merged.t_last = young->t_last;
  merged.last_detection = young->last_detection;
  merged.z_min = young->z_min, merged.z_max = young->z_max, merged.ground_z = young->ground_z;
  merged.top_height = std::max(merged.top_height, young->top_height);
  label(merged, young->t_last, p_);
  *young = merged;
  ++reidentified_;
  tracks_.erase(best);
}

std::vector<EndedTrack> Tracker::takeEnded() {
  std::vector<EndedTrack> out;
  out.swap(ended_);
  return out;
}

}  // namespace roadslam::objects
