#include "roadslam/objects/stage.h"

#include "roadslam/objects/track_box.h"
#include "roadslam/runfolder/objects_csv.h"

#include <algorithm>
#include <chrono>
#include <cmath>


namespace roadslam::objects {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kHalfSweep_s = 0.05;  // half a turn at 10 Hz: how far from the sweep's time a point may be
constexpr size_t kFreeSamples = 64;  // points of an object checked against the earlier sweep
constexpr double kRetroStep_s = 0.1;   // extrapolated boxes every sweep at 10 Hz (the keyframes match within half)

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

/// \p b's floor lowered to \p floor_m above the ground under \p t's last detection (never raised;
/// \p floor_m < 0: as it is). OrientedBox::contains subtracts \p margin_m again.
void lowerFloor(OrientedBox& b, const Track& t, double floor_m, double margin_m) {
  if (floor_m >= 0) b.z_min_m = std::min(b.z_min_m, t.ground_z + floor_m + margin_m);
}

}  // namespace

ObjectsFrame ObjectsStage::snapshot() const {
  ObjectsFrame f;
  const TrackerParams& tp = tracker_.params();
  for (const Track& t : tracker_.tracks()) {
    if (t.state != TrackState::Confirmed) continue;
    if (t.misses <= tp.output_max_misses) f.tracks.push_back(t);
    if (!t.moving) continue;  // the removal boxes keep every coasting moving track: their points may be there
    BoxRecord b{t.t_last, movingTrackBox(t, tp, kHalfSweep_s)};
    lowerFloor(b.box, t, p_.removal_floor_m, p_.removal_margin_m);
    f.moving_boxes.push_back(b);
  }
  return f;
}

ObjectsFrame ObjectsStage::process(const Scan& scan, const Eigen::Isometry3d& T_map_lidar, double t_s) {
  auto t0 = Clock::now();
  const auto g = objectGroundLabels(scan.points, p_);
  const double ms_ground = msSince(t0);
  t0 = Clock::now();
  SegmentationStats st;
  std::vector<Object> objs = segmentObjects(scan.points, scan.has_rings, g.ground, g.height_above_ground_m, p_, &st);
  const double ms_segment = msSince(t0);
  // a moving object is seen when the beam sweeps over it, up to half a turn from the reference time
  for (Object& o : objs) o.dt_s = scan.has_point_times ? scan.stamp_s + o.t_mean - t_s : 0.0;
  t0 = Clock::now();  // the free-space evidence is the moving label's: its time is the tracking's
  if (p_.free_space_lag_s > 0) {
    checkFreeSpace(objs, scan, T_map_lidar, t_s);
    free_.add(scan, T_map_lidar, t_s);
  }
  std::vector<Track> before;
  if (p_.forward_extrapolate_s > 0) {
    for (const Track& t : tracker_.tracks()) {
      if (t.moving && t.state == TrackState::Confirmed) before.push_back(t);
    }
  }
  tracker_.update(t_s, T_map_lidar, objs);
  ObjectsFrame f = snapshot();
  forwardBoxes(f, before, t_last_update_, t_s, T_map_lidar.translation().head<2>());
  t_last_update_ = t_s;
  f.object_track.assign(objs.size(), -1);
  f.object_moving.assign(objs.size(), 0);
  for (const Track& t : tracker_.tracks()) {
    if (t.last_detection < 0 || t.state != TrackState::Confirmed) continue;
    f.object_track[static_cast<size_t>(t.last_detection)] = t.id;
    f.object_moving[static_cast<size_t>(t.last_detection)] = t.moving;
  }
  for (const Track& t : tracker_.tracks()) {
    if (!t.moving || t.moving_since != t_s) continue;
    const size_t first = f.retro.size();
    f.retro.insert(f.retro.end(), t.history->begin(), t.history->end());
    // the car drove where its velocity leads back: car-sized boxes along that path since its birth (the
    // parts of the car its detections missed) and for p_.retro_extrapolate_s before (seen too far or
    // too sparse for an object)
    const TrackerParams& tp = tracker_.params();
    const int steps = static_cast<int>(std::floor((t_s - t.t_birth + p_.retro_extrapolate_s) / kRetroStep_s + 1e-9));
    const OrientedBox box = movingTrackBox(t, tp, kHalfSweep_s);
    for (int k = 1; k <= steps; ++k) {
      BoxRecord b{t_s - k * kRetroStep_s, box};
      b.box.centre_m = t.x.head<2>() - t.x.tail<2>() * (t_s - b.t);
      f.retro.push_back(b);
    }
    for (size_t k = first; k < f.retro.size(); ++k) lowerFloor(f.retro[k].box, t, p_.removal_floor_m, p_.removal_margin_m);
  }
  f.ms_track = msSince(t0);
  f.objects = std::move(objs);
  f.stats = st;
  f.ms_ground = ms_ground, f.ms_segment = ms_segment;
  return f;
}

void ObjectsStage::checkFreeSpace(std::vector<Object>& objs, const Scan& scan, const Eigen::Isometry3d& T_map_lidar,
                                  double t_s) const {
  for (Object& o : objs) {
    const FreeEvidence e = free_.check(samplePointsInMap(scan, o.indices, T_map_lidar, kFreeSamples), t_s,
                                       p_.free_space_lag_s, p_.free_space_margin_m);
    o.free_through = e.through, o.free_hit = e.hit;
  }
}

ObjectsFrame ObjectsStage::coast(double t_s) {
  tracker_.coast(t_s, "pose");
  ended_moving_.clear();  // a pose gap ends every track: none of them left the sensor's reach
  return snapshot();
}

void ObjectsStage::forwardBoxes(ObjectsFrame& f, const std::vector<Track>& before, double t_before, double t_s,
                                const Eigen::Vector2d& lidar_xy) {
  if (p_.forward_extrapolate_s <= 0) return;
  for (const Track& b : before) {
    bool alive = false;
    for (const Track& t : tracker_.tracks()) alive = alive || t.id == b.id;
    if (!alive) ended_moving_.push_back({b, t_before});
  }
  const TrackerParams& tp = tracker_.params();
  std::vector<EndedMoving> keep;
  for (const EndedMoving& e : ended_moving_) {
    const double dt = t_s - e.t;
    const Track& t = e.track;
    const Eigen::Vector2d centre = t.x.head<2>() + t.x.tail<2>() * dt;
    // beyond the sweeps' reach it leaves no point
    if (dt > p_.forward_extrapolate_s || (centre - lidar_xy).norm() > p_.max_range_m + t.length) continue;
    keep.push_back(e);
    BoxRecord b{t_s, movingTrackBox(t, tp, kHalfSweep_s)};
    b.box.centre_m = centre;
    lowerFloor(b.box, t, p_.removal_floor_m, p_.removal_margin_m);
    f.moving_boxes.push_back(b);
  }
  ended_moving_ = std::move(keep);
}

size_t removeMovingPoints(std::vector<Eigen::Vector3d>& pts_lidar, const ObjectsFrame& f, double margin_m,
                          const Eigen::Isometry3d& T_map_lidar) {
  std::vector<const Object*> moving;
  for (size_t k = 0; k < f.objects.size() && k < f.object_moving.size(); ++k) {
    if (f.object_moving[k]) moving.push_back(&f.objects[k]);
  }
  if (moving.empty() && f.moving_boxes.empty()) return 0;
  const size_t before = pts_lidar.size();
  auto inside = [&](const Eigen::Vector3d& q) {
    for (const Object* o : moving) {
      if (o->box.contains(q, margin_m)) return true;
    }
    if (f.moving_boxes.empty()) return false;
    const Eigen::Vector3d q_map = T_map_lidar * q;
    for (const BoxRecord& b : f.moving_boxes) {
      if (b.box.contains(q_map, margin_m)) return true;
    }
    return false;
  };
  pts_lidar.erase(std::remove_if(pts_lidar.begin(), pts_lidar.end(), inside), pts_lidar.end());
  return before - pts_lidar.size();
}

std::string objectsCsvHeader() { return runfolder::objectsCsvHeader(); }

std::string objectsCsvRows(size_t frame, double stamp_s, const Eigen::Isometry3d& T_map_lidar, const ObjectsFrame& f) {
  std::string out;
  for (size_t k = 0; k < f.objects.size(); ++k) {
    const Object& o = f.objects[k];
    runfolder::ObjectRow r;
    r.frame = frame, r.stamp_s = stamp_s, r.object = k, r.box = o.box.placed(T_map_lidar);
    r.points = o.points, r.track_id = k < f.object_track.size() ? f.object_track[k] : -1;
    out += runfolder::objectsCsvRow(r);
  }
  return out;
}

std::string tracksCsvHeader() { return runfolder::tracksCsvHeader(); }

std::string tracksCsvRows(size_t frame, double stamp_s, const ObjectsFrame& f) {
  std::string out;
  for (const Track& t : f.tracks) {
    runfolder::TrackRow r;
    r.frame = frame, r.stamp_s = stamp_s, r.track_id = t.id, r.box = t.box(), r.vx = t.x(2), r.vy = t.x(3);
    r.speed_mps = t.speed(), r.moving = t.moving, r.hits = t.hits, r.misses = t.misses;
    r.age_s = stamp_s - t.t_birth;
    out += runfolder::tracksCsvRow(r);
  }
  return out;
}

std::string endedCsvHeader() { return runfolder::tracksEndedCsvHeader(); }

std::string endedCsvRows(const std::vector<EndedTrack>& ended) {
  std::string out;
  for (const EndedTrack& e : ended) {
    runfolder::EndedTrackRow r;
    r.track_id = e.track.id, r.t_birth = e.track.t_birth, r.t_end = e.t_end, r.hits = e.track.hits;
    r.confirmed = e.track.state == TrackState::Confirmed, r.moving = e.track.moving, r.reason = e.reason;
    out += runfolder::tracksEndedCsvRow(r);
  }
  return out;
}

}  // namespace roadslam::objects
