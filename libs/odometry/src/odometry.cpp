#include "roadslam/odometry/odometry.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_set>

#include "roadslam/odometry/deskew.h"
#include "roadslam/odometry/weak_directions.h"
#include "roadslam/common/sweep_timing.h"
#include "roadslam/common/voxel_hash.h"

namespace roadslam::odometry {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// The first point in each cubic voxel of \p voxel_m, with its ground flag.
void firstPerVoxel(const std::vector<Eigen::Vector3d>& pts, const std::vector<uint8_t>& ground,
                   double voxel_m, std::vector<Eigen::Vector3d>& out, std::vector<uint8_t>& out_ground) {
  std::unordered_set<Eigen::Vector3i, VoxelKeyHash> seen;
  seen.reserve(pts.size());
  out.clear();
  out_ground.clear();
  for (size_t i = 0; i < pts.size(); ++i) {
    if (!seen.insert((pts[i] / voxel_m).array().floor().cast<int>()).second) continue;
    out.push_back(pts[i]);
    out_ground.push_back(ground.empty() ? 0 : ground[i]);
  }
}

/// Road points beyond \p max_range_m [m, lidar frame] leave the map: a small pitch error moves them
/// vertically by range x pitch, and the map would hand that height on to the vehicle later.
void dropFarGround(std::vector<Eigen::Vector3d>& pts, std::vector<uint8_t>& ground, double max_range_m) {
  if (max_range_m <= 0 || ground.empty()) return;
  const double r2 = max_range_m * max_range_m;
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (ground[i] && pts[i].head<2>().squaredNorm() > r2) continue;
    pts[k] = pts[i];
    ground[k++] = ground[i];
  }
  pts.resize(k);
  ground.resize(k);
}

double angleOf(const Eigen::Isometry3d& T) {
  return Eigen::AngleAxisd(T.rotation()).angle();
}

/// Constant-velocity scaling of a motion: s = 0 identity, s = 1 \p T, s = 2 twice \p T (slerp/lerp).
Eigen::Isometry3d scaleMotion(const Eigen::Isometry3d& T, double s) {
  const Eigen::AngleAxisd aa(T.rotation());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::AngleAxisd(aa.angle() * s, aa.axis()).toRotationMatrix();
  out.translation() = T.translation() * s;
  return out;
}

/// Time steps shorter than this fraction of a sweep do not measure a velocity [-].
constexpr double kMinVelocityStep = 0.25;

}  // namespace

const char* toString(FrameStatus s) {
  switch (s) {
    case FrameStatus::Ok: return "ok";
    case FrameStatus::First: return "first";
    case FrameStatus::Standstill: return "standstill";
    case FrameStatus::Degenerate: return "degenerate";
    case FrameStatus::NotConverged: return "not_converged";
    case FrameStatus::Skipped: return "skipped";
    case FrameStatus::Empty: return "empty";
  }
  return "?";
}

Odometry::Odometry(Params params)
    : params_(std::move(params)),
      chain_(params_.preprocess),
      matcher_(makeScanMatcher(params_)),
      threshold_(params_.initial_threshold_m, params_.min_motion_m, params_.max_range_m) {}

Odometry::~Odometry() = default;

Eigen::Isometry3d Odometry::predict(const std::optional<MotionPrior>& prior) const {
  if (prior) return prior->T_prev_curr;
  return track_.delta_last;
}

bool Odometry::isStandstill(const Eigen::Isometry3d& delta, const std::optional<MotionPrior>& prior) const {
  if (prior) return std::abs(prior->speed_mps) < params_.standstill_speed_mps;
  return delta.translation().norm() < params_.standstill_translation_m &&
         angleOf(delta) < params_.standstill_rotation_rad;
}

void Odometry::applyPriorOnWeakDirections(const WeakBasis& weak, double lever_m, const Eigen::Isometry3d& T_pred,
                                          Eigen::Isometry3d& T_est, bool about_sensor) const {
  // Correction of the registration over the prediction, [t, L*r]; its components along the weak
  // directions are not observed by the scan, so they are removed (Zhang et al. 2016, solution
  // remapping). The spectrum's weak eigenvectors are in the registration's convention, a left
  // increment in the world frame. The motion axis is a direction of the sensor's own displacement:
  // measured as the world-frame increment's translation, t_est - R_corr t_pred, a yaw correction of
  // 0.5 deg 63 m from the world's origin moved the sensor 0.55 m along it (the simulated parking lot
  // from its pcap ran backwards at 14 m/s), so there the correction is taken about the sensor.
  const Eigen::Isometry3d corr = T_est * T_pred.inverse();
  const Eigen::AngleAxisd aa(corr.rotation());
  const double L = lever_m;
  Eigen::Matrix<double, 6, 1> xi;
  const Eigen::Vector3d t = about_sensor ? Eigen::Vector3d(T_est.translation() - T_pred.translation()) : corr.translation();
  xi << t, aa.axis() * aa.angle() * L;
  xi -= weak * (weak.transpose() * xi);
  Eigen::Isometry3d kept = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d rv = xi.tail<3>() / L;
  if (rv.norm() > 0) kept.linear() = Eigen::AngleAxisd(rv.norm(), rv.normalized()).toRotationMatrix();
  if (about_sensor) {
    T_est.linear() = kept.linear() * T_pred.linear();
    T_est.translation() = T_pred.translation() + xi.head<3>();
    return;
  }
  kept.translation() = xi.head<3>();
  T_est = kept * T_pred;
}

void Odometry::judgeDegeneracy(const registration::RegistrationResult& r, const registration::SurfaceInformation& surface,
                               const Eigen::Isometry3d& T_pred, const std::optional<MotionPrior>& prior,
                               Eigen::Isometry3d& T_est, FrameResult& res) const {
  // Along the predicted motion the scans may measure nothing real while ring-pattern voxels and
  // the full 6x6 spectrum look healthy (a tunnel): the motion's own information decides too.
  const Eigen::Vector3d motion = T_pred.translation() - track_.T_world_last.translation();
  const Eigen::Vector3d n = motion.normalized();
  if (matcher_->measuresSurface() && track_.motion_known && motion.norm() >= params_.standstill_translation_m) {
    res.motion_information = surface.along(n);
  }
  // Constant velocity is only as good as the motion it repeats: without a prior it replaces the
  // scans only once a frame's scans clearly saw the motion (motion_seen_threshold), and until the
  // car stands or tracking fails. The simulated highway's standing start, whose first motion was
  // a few decimetres of noise, had carried that on (RTE 0.16 -> 2 %); its slow, open start
  // (0.001-0.01 along the motion) then lost 15 % RTE to constant velocity while accelerating.
  const bool weak_motion = (prior || track_.motion_seen) &&
                           res.motion_information < params_.motion_degeneracy_threshold;
  // The full spectrum's weak eigenvectors mix rotation with translation and fall below the
  // threshold on open roads too: only an external prior replaces them (constant velocity there
  // tilted the simulated tunnel's approach by 9 deg). Along the motion, constant velocity is the
  // best guess left without one.
  const bool weak_eigen = r.degeneracy.degenerate && params_.use_prior_on_degeneracy && prior;
  // Where the spectrum found weak eigenvectors they are the prior's, as before; adding the motion
  // axis to them measured no better (simulated tunnel with the CAN prior: RTE 0.296 vs 0.294 %).
  if (weak_eigen || weak_motion) {
    const WeakBasis weak = weakBasis(weak_eigen ? r.degeneracy : registration::Degeneracy{},
                                     weak_motion && !weak_eigen ? &n : nullptr);
    applyPriorOnWeakDirections(weak, r.degeneracy.length_scale_m, T_pred, T_est, !weak_eigen);
    res.information = reduceInformation(r.information, surface.information, weak, r.degeneracy.length_scale_m);
    res.status = FrameStatus::Degenerate;
  }
}

void Odometry::updateUp(const FrameResult& res) {
  // The world's up direction: every frame's structures rotated into the world frame and summed
  // (robustly around the current estimate), so early errors average out; the prior pulls each new
  // frame's tilt towards it. Once frames are many, a drifting pose moves it by 1/N only.
  const double kernel = up_.frames > 0 ? params_.gravity_kernel_rad : 0.0;
  up_.scatter += verticalScatter(frame_.vertical, res.T_world_lidar.linear(), up_.world, kernel);
  Eigen::Vector2d info;
  const Eigen::Vector3d up = upFromScatter(up_.scatter, up_.world, &info);
  if (info.minCoeff() < params_.gravity_min_information) return;
  up_.world = up;
  ++up_.frames;
}

void Odometry::updateKeyframe(FrameResult& res) {
  const Eigen::Isometry3d d = track_.T_world_keyframe.inverse() * res.T_world_lidar;
  if (res.status == FrameStatus::First || d.translation().norm() >= params_.keyframe_distance_m ||
      angleOf(d) >= params_.keyframe_angle_rad) {
    res.keyframe = true;
    track_.T_world_keyframe = res.T_world_lidar;
  }
}

registration::RegistrationResult Odometry::match(const std::vector<Eigen::Vector3d>& source,
                                                 const Eigen::Isometry3d& T_pred, FrameResult& res,
                                                 registration::SurfaceInformation* surface) {
  registration::Params rp = params_.registration;
  if (params_.adaptive_threshold) {
    // AdaptiveThreshold gives tau = 3 sigma (Vizzo et al. 2023, eq. 7); KISS-ICP pairs points
    // within 3 sigma and scales its kernel at sigma / 3. Pairing within 3 tau lets passing traffic
    // in on an open road.
    const double sigma =
        std::clamp(threshold_.threshold() / 3.0, params_.min_threshold_m, params_.max_threshold_m);
    rp.max_correspondence_distance_m = matcher_->correspondenceDistance(3.0 * sigma);
    rp.kernel_scale_m = sigma / 3.0;
  }
  res.threshold_m = rp.max_correspondence_distance_m;
  registration::GravityPrior g;
  g.constraints = &frame_.vertical;
  g.up_map = up_.world;
  g.scale_m2 = params_.gravity_weight_m2;
  g.kernel_rad = params_.gravity_kernel_rad;
  return matcher_->align(source, T_pred, rp, usesGravityPrior() && up_.frames > 0 ? &g : nullptr, surface);
}

Eigen::Isometry3d Odometry::searchFirstMotion(const Scan& scan, const Eigen::Isometry3d& guess,
                                              FrameResult& res) {
  // Scan to scan against the first sweep, both as recorded: at 15 m/s the sweeps are 1.5 m apart,
  // beyond the voxel map's reach (its neighbour voxels) and its 0.2-0.7 m kernel. A coarse NDT level
  // of 8 m cells sees that far (Magnusson 2009, Sec. 6.2.4: multi-resolution widens the basin).
  registration::Params rp;
  rp.method = registration::Method::Ndt;
  rp.ndt_resolution_m = 2.0;
  rp.ndt_levels = 3;
  rp.max_iterations = 40;
  rp.max_correction_m = 15.0;
  const auto target_pts = registration::voxelDownsample(frame_.points, 0.5);
  const auto source = registration::voxelDownsample(deskew(scan, Eigen::Isometry3d::Identity(), 1.0), 0.5);
  const registration::Target target(target_pts, rp);
  const auto r = registration::align(target, source, guess, rp);
  if (!r.converged) {
    res.reason = "first motion search: " + registration::toString(r.status);
    return guess;
  }
  // NDT's coarse cells can also slide a standing car along a row of parked cars by a car's length:
  // the matcher itself, from either start, says which motion the map explains better.
  const auto fine = registration::voxelDownsample(deskew(scan, Eigen::Isometry3d::Identity(), 1.0),
                                                  params_.registration_voxel_m);
  FrameResult scratch;
  const auto from_guess = match(fine, track_.T_world_last * guess, scratch);
  const auto from_search = match(fine, track_.T_world_last * r.T_target_source, scratch);
  // The better of the two, judged as the odometry judges a frame: converged, then the points it
  // explains, then their spread. Its motion also deskews the first sweep and this one.
  const auto better = [](const registration::RegistrationResult& a, const registration::RegistrationResult& b) {
    if (a.converged != b.converged) return a.converged;
    if (std::abs(a.inliers - b.inliers) > 0.005 * std::max(a.inliers, b.inliers)) return a.inliers > b.inliers;
    return a.fitness <= b.fitness;
  };
  const auto& best = better(from_search, from_guess) ? from_search : from_guess;
  return track_.T_world_last.inverse() * best.T_target_source;
}

void Odometry::redeskewFirstFrame(const Eigen::Isometry3d& delta_sweep) {
  // The first sweep went into the map as recorded (its motion was unknown); with the motion known it
  // is deskewed like every other sweep and the map built again from it.
  const double ref = first_scan_->has_point_times ? params_.deskew_reference : 0.0;
  frame_.points = deskew(*first_scan_, delta_sweep, params_.sweep_duration_s, ref);
  matcher_->clear();
  updateMap(track_.T_world_last, track_.last_stamp_s);
  first_scan_.reset();
}

bool MapExclusion::contains(const Eigen::Vector3d& p, double t_s) const {
  OrientedBox moved = box;
  moved.centre_m += velocity_world_mps * (t_s - stamp_s);
  return moved.contains(p);
}

size_t Odometry::setMapExclusions(std::vector<MapExclusion> boxes) {
  exclusions_ = std::move(boxes);
  constexpr double kStep_s = 0.05;  // half a sweep: a car at 15 m/s moves 0.75 m, inside its margins
  size_t erased = 0;
  for (const MapExclusion& b : exclusions_) {
    if (b.erase_back_s <= 0) continue;
    erased += matcher_->eraseVoxels([&](const Eigen::Vector3d& mean) {
      for (double dt = 0; dt <= b.erase_back_s + 1e-9; dt += kStep_s) {
        if (b.contains(mean, b.stamp_s - dt)) return true;
      }
      return false;
    });
  }
  return erased;
}

int Odometry::updateMap(const Eigen::Isometry3d& T_world_lidar, double stamp_s) {
  // A bounded number of points of each frame per map voxel (KISS-ICP inserts the frame voxelised at
  // half the map voxel): a voxel then fills from several frames and rings, so the scan line of one
  // ring across the road never fills it alone.
  std::vector<Eigen::Vector3d> world;
  std::vector<uint8_t> ground;
  firstPerVoxel(frame_.points, frame_.ground, params_.map_insert_voxel_m, world, ground);
  dropFarGround(world, ground, params_.map_ground_max_range_m);
  for (auto& p : world) p = T_world_lidar * p;
  int excluded = 0;
  if (!exclusions_.empty()) {
    size_t k = 0;
    for (size_t i = 0; i < world.size(); ++i) {
      const bool out = std::any_of(exclusions_.begin(), exclusions_.end(),
                                   [&](const MapExclusion& b) { return b.contains(world[i], stamp_s); });
      if (out) {
        ++excluded;
        continue;
      }
      world[k] = world[i];
      if (!ground.empty()) ground[k] = ground[i];
      ++k;
    }
    world.resize(k);
    if (!ground.empty()) ground.resize(k);
  }
  matcher_->addToMap(world, ground, T_world_lidar.translation());
  return excluded;
}

Odometry::Prediction Odometry::predictFrame(const Scan& scan, const std::optional<MotionPrior>& prior,
                                            FrameResult& res) {
  Prediction p;
  // constant velocity: the last motion rescaled to this frame's time step
  p.dt = track_.have_pose ? scan.stamp_s - track_.last_stamp_s : params_.sweep_duration_s;
  p.delta = predict(prior);
  if (!prior && track_.have_pose && p.dt > 0 && track_.last_dt_s > 0) p.delta = scaleMotion(p.delta, p.dt / track_.last_dt_s);
  p.first_motion = track_.have_pose && !track_.motion_known;
  if (p.first_motion && !prior && params_.first_motion_search) p.delta = searchFirstMotion(scan, p.delta, res);
  p.T_world = track_.T_world_last * p.delta;
  p.delta_sweep = scaleMotion(p.delta, p.dt > 0 && track_.have_pose ? params_.sweep_duration_s / p.dt : 1.0);
  return p;
}

void Odometry::deskewFrame(Scan& scan, const Prediction& pred, FrameResult& res) {
  if (params_.times_from_azimuth && !scan.has_point_times) {
    timesFromAzimuth(scan, SweepTiming{params_.sweep_duration_s, SpinDirection::Clockwise, 180.0, StampReference::Start});
  }
  res.point_times = pointTimesName(scan);
  res.deskewed = params_.deskew && scan.has_point_times;
  if (!params_.deskew) scan.has_point_times = false;  // deskew() then keeps the points as they are
  if (pred.first_motion && first_scan_ && params_.deskew) redeskewFirstFrame(pred.delta_sweep);
  first_scan_.reset();
  const double ref = scan.has_point_times ? params_.deskew_reference : 0.0;
  res.stamp_s = poseTimeOf(scan);
  frame_.points = deskew(scan, pred.delta_sweep, params_.sweep_duration_s, ref);
  if (params_.ground_aware_map) frame_.ground = preprocess::segmentGround(scan.points, params_.preprocess.ground_seg);
  if (usesGravityPrior()) {
    const Eigen::Vector3d up_guess = track_.have_pose ? Eigen::Vector3d(pred.T_world.linear().transpose() * up_.world)
                                                      : Eigen::Vector3d::UnitZ();
    frame_.vertical = findVerticalStructures(frame_.points, frame_.ground, up_guess, params_.vertical);
    res.vertical_constraints = static_cast<int>(frame_.vertical.size());
  }
}

bool Odometry::startTrack(const Scan& scan, size_t source_points, FrameResult& res) {
  res.status = source_points == 0 ? FrameStatus::Empty : FrameStatus::First;
  if (source_points == 0) return false;
  res.T_world_lidar = Eigen::Isometry3d::Identity();
  if (params_.first_motion_search && params_.deskew && scan.has_point_times) first_scan_ = scan;
  return true;
}

void Odometry::registerFrame(const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& T_pred,
                             const std::optional<MotionPrior>& prior, FrameResult& res) {
  registration::SurfaceInformation surface;
  const auto r = match(source, T_pred, res, &surface);
  res.iterations = r.iterations;
  res.inliers = r.inliers;
  res.fitness_m = r.fitness;
  res.information = r.information;
  res.weak_directions = r.degeneracy.num_weak;
  res.min_eigenvalue = r.degeneracy.eigenvalues(0);
  Eigen::Isometry3d T_est = r.T_target_source;
  const bool usable = r.converged || (r.status == registration::Status::MaxIterations &&
                                      r.inliers >= params_.min_inlier_fraction * source.size());
  if (!usable) {
    res.status = source.empty() ? FrameStatus::Empty : FrameStatus::NotConverged;
    res.reason = registration::toString(r.status) + (r.reason.empty() ? "" : ": " + r.reason);
    T_est = T_pred;
  } else {
    judgeDegeneracy(r, surface, T_pred, prior, T_est, res);
  }
  const Eigen::Isometry3d delta = track_.T_world_last.inverse() * T_est;
  if (res.status == FrameStatus::Ok && isStandstill(delta, prior)) {
    res.status = FrameStatus::Standstill;
    T_est = track_.T_world_last;
  }
  if (res.status == FrameStatus::Ok || res.status == FrameStatus::Degenerate) {
    threshold_.update(T_pred.inverse() * T_est, delta);
  }
  res.T_world_lidar = T_est;
  const bool tracking = res.status == FrameStatus::Ok || res.status == FrameStatus::Degenerate;
  track_.motion_seen = prior || (tracking && track_.motion_seen) ||
                       (res.status == FrameStatus::Ok && res.motion_information >= params_.motion_seen_threshold);
}

void Odometry::advance(FrameResult& res, const std::optional<MotionPrior>& prior, double dt, double stamp_s) {
  // The velocity is the motion over the time step; over a step much shorter than a sweep (the
  // partial sweep a packet gap leaves, 1.3 ms before the next) the registration's few centimetres of
  // correction became 240 m/s and the next prediction diverged (a pcap with 0.5 s cut out: 94 of
  // 196 frames not converged). Such a step keeps the velocity it had.
  if (track_.have_pose && dt > kMinVelocityStep * params_.sweep_duration_s) {
    track_.delta_last = track_.T_world_last.inverse() * res.T_world_lidar;
    track_.last_dt_s = dt;
  }
  if (res.status == FrameStatus::Standstill) track_.delta_last = Eigen::Isometry3d::Identity();
  if (res.status == FrameStatus::Ok || res.status == FrameStatus::Degenerate ||
      res.status == FrameStatus::Standstill || (prior && track_.have_pose)) {
    track_.motion_known = true;
  }
  track_.T_world_last = res.T_world_lidar;
  track_.last_stamp_s = stamp_s;
  track_.have_pose = true;
  updateKeyframe(res);
}

FrameResult Odometry::process(Scan scan, const std::optional<MotionPrior>& given_prior) {
  const auto t0 = Clock::now();
  FrameResult res;
  // A non-finite prior (a decoding fault upstream) would become the pose and stay in every later one.
  const bool prior_bad = given_prior && !(given_prior->T_prev_curr.matrix().allFinite() &&
                                          std::isfinite(given_prior->speed_mps));
  const std::optional<MotionPrior> prior = prior_bad ? std::nullopt : given_prior;
  res.index = track_.frames++;
  res.stamp_s = scan.stamp_s;
  res.points_in = static_cast<int>(scan.points.size());
  const auto report = chain_.process(scan);
  res.ms_preprocess = msSince(t0);
  if (report.skipped) {
    res.status = FrameStatus::Skipped;
    return res;
  }
  const Prediction pred = predictFrame(scan, prior, res);
  deskewFrame(scan, pred, res);

  const auto t_reg = Clock::now();
  const auto source = registration::voxelDownsample(frame_.points, params_.registration_voxel_m);
  res.points_registered = static_cast<int>(source.size());
  if (!track_.have_pose) {
    if (!startTrack(scan, source.size(), res)) return res;
  } else {
    registerFrame(source, pred.T_world, prior, res);
  }
  res.ms_register = msSince(t_reg);

  if (usesGravityPrior() && (res.status == FrameStatus::Ok || res.status == FrameStatus::First)) updateUp(res);
  const auto t_map = Clock::now();
  if (res.status == FrameStatus::Ok || res.status == FrameStatus::First || res.status == FrameStatus::Degenerate) {
    res.map_points_excluded = updateMap(res.T_world_lidar, res.stamp_s);
  }
  res.ms_map = msSince(t_map);
  advance(res, prior, pred.dt, scan.stamp_s);
  if (prior_bad) res.reason = "motion prior not finite, ignored" + (res.reason.empty() ? "" : "; " + res.reason);
  res.ms_total = msSince(t0);
  return res;
}

}  // namespace roadslam::odometry
