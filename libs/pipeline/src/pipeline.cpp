#include "roadslam/pipeline/pipeline.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "roadslam/mapping/mapper.h"
#include "roadslam/mapping/octo_worker.h"

namespace roadslam::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

/// A source whose first sweep was read ahead (openNonEmptySource); everything else is the source's.
class PeekedSource : public sources::ScanSource {
 public:
  PeekedSource(std::unique_ptr<sources::ScanSource> src, Scan first) : src_(std::move(src)), first_(std::move(first)) {}
  std::optional<Scan> next() override {
    if (first_) {
      std::optional<Scan> s = std::move(first_);
      first_.reset();
      return s;
    }
    return src_->next();
  }
  bool finished() const override { return !first_ && src_->finished(); }
  std::vector<sources::TimedGpsFix> takeGpsFixes() override { return src_->takeGpsFixes(); }
  std::string describe() const override { return src_->describe(); }
  sources::ScanSourceStats stats() const override { return src_->stats(); }
  size_t sizeHint() const override { return src_->sizeHint(); }
  std::string errorMessage() const override { return src_->errorMessage(); }
  std::vector<std::string> warnings() const override { return src_->warnings(); }

 private:
  std::unique_ptr<sources::ScanSource> src_;
  std::optional<Scan> first_;
};

/// The OctoMap follows the graph: a new keyframe is queued, a loop closure rebuilds it at the new poses.
}  // namespace

StageTimes& StageTimes::operator+=(const StageTimes& o) {
  source += o.source, poses += o.poses, deskew += o.deskew, maps += o.maps, boundaries += o.boundaries;
  objects += o.objects;
  return *this;
}

Pipeline::Pipeline(std::unique_ptr<sources::ScanSource> source, Stages stages)
    : source_(std::move(source)), stages_(std::move(stages)) {
  if (!source_) throw std::invalid_argument("Pipeline: no source");
  if (!stages_.poses) throw std::invalid_argument("Pipeline: no pose stage");
}

Pipeline::~Pipeline() = default;

/// Keyframes go to the OctoMap once older than octomap_delay_s (every keyframe when \p flush); after a
/// loop, the OctoMap is rebuilt from the keyframes decided on so far at their moved poses.
void Pipeline::feedOctoMap(bool loop, double now_s, bool flush) {
  if (!stages_.octomap || !stages_.mapper) return;
  const mapping::Mapper& mapper = *stages_.mapper;
  const auto& kfs = mapper.keyframes();
  const double spacing = stages_.octomap_keyframe_spacing_m;
  if (loop) {
    mapping::PoseVector poses = mapper.keyframePoses();
    poses.resize(std::min(poses.size(), octo_seen_));
    stages_.octomap->rebuild(mapping::octoMapItems(kfs, poses, spacing));
  }
  for (; octo_seen_ < kfs.size() && (flush || kfs[octo_seen_].stamp_s <= now_s - stages_.octomap_delay_s); ++octo_seen_) {
    if (mapping::takesOctoMap(kfs, octo_seen_, spacing)) {
      stages_.octomap->push({kfs[octo_seen_].points_lidar, mapper.graph().pose(octo_seen_)});
    }
  }
}

constexpr double kRetroMatch_s = 0.049;  // a box applies to the keyframe within half a sweep (10 Hz) of its time

/// Drops from the keyframes the points inside \p boxes (map frame, grown by removal_margin_m) of the
/// keyframes made at the boxes' times (a keyframe's stamp is its odometry frame's, the objects' time).
size_t Pipeline::removeRetro(const std::vector<objects::BoxRecord>& boxes) {
  if (!stages_.mapper || boxes.empty()) return 0;
  const auto& kfs = stages_.mapper->keyframes();
  double t_first = boxes.front().t;
  for (const auto& b : boxes) t_first = std::min(t_first, b.t);
  size_t removed = 0;
  for (size_t k = kfs.size(); k-- > 0 && kfs[k].stamp_s >= t_first - kRetroMatch_s;) {
    const Eigen::Isometry3d T_odom_lidar = kfs[k].T_odom_lidar;
    std::vector<const objects::BoxRecord*> here;
    for (const auto& b : boxes) {
      if (std::abs(b.t - kfs[k].stamp_s) < kRetroMatch_s) here.push_back(&b);
    }
    if (here.empty()) continue;
    removed += stages_.mapper->erasePoints(k, [&](const Eigen::Vector3f& q) {
      const Eigen::Vector3d p_map = T_odom_lidar * q.cast<double>();
      for (const auto* b : here) {
        if (objects::insideBox(*b, p_map, stages_.removal_margin_m)) return true;
      }
      return false;
    });
  }
  return removed;
}

std::optional<PipelineFrame> Pipeline::next() {
  PipelineFrame f;
  auto t = Clock::now();
  std::optional<Scan> scan = source_->next();
  f.ms.source = msSince(t);
  if (!scan) {
    if (source_->finished()) feedOctoMap(false, 0, true);
    return std::nullopt;
  }
  f.index = frames_++;

  t = Clock::now();
  f.pose = stages_.poses->pose(*scan);
  f.ms.poses = msSince(t);

  // deskew, then objects before the maps: the maps may leave the moving objects' points out
  const bool bounds = stages_.boundaries && stages_.boundary_use != BoundaryUse::None;
  const bool keep = bounds || stages_.objects;
  if (keep && f.pose.ok) {
    t = Clock::now();
    deskewToReference(*scan, f.pose);
    f.ms.deskew = msSince(t);
  }
  if (stages_.objects) {
    t = Clock::now();
    f.objects = f.pose.ok ? stages_.objects->process(*scan, f.pose.ref, f.pose.t_ref) : stages_.objects->coast(f.pose.stamp_s);
    if (stages_.remove_moving_from_odometry) {
      const double t_tracks = f.pose.ok ? f.pose.t_ref : f.pose.stamp_s;
      stages_.poses->excludeFromMap(
          movingExclusions(*f.objects, t_tracks, stages_.objects->tracker().params(), stages_.removal_margin_m, 0.1,
                           stages_.odometry_erase_back_s));
    }
    f.ms.objects = msSince(t);
  }

  if (stages_.mapper) {
    if (!f.pose.odometry || !f.pose.points_lidar) throw std::logic_error("Pipeline: the maps stage needs the odometry's poses");
    t = Clock::now();
    std::optional<mapping::WheelMotion> wheel;
    if (f.pose.T_baseprev_basecurr) wheel = mapping::WheelMotion{*f.pose.T_baseprev_basecurr, f.pose.T_base_lidar};
    if (stages_.remove_moving_from_maps && f.objects && f.pose.ok) {
      std::vector<Eigen::Vector3d> pts = *f.pose.points_lidar;
      f.moving_points_removed = objects::removeMovingPoints(pts, *f.objects, stages_.removal_margin_m, f.pose.ref);
      f.loop_closed = stages_.mapper->addFrame(*f.pose.odometry, pts, wheel);
      f.retro_points_removed = removeRetro(f.objects->retro);
    } else {
      f.loop_closed = stages_.mapper->addFrame(*f.pose.odometry, *f.pose.points_lidar, wheel);
    }
    feedOctoMap(f.loop_closed, f.pose.t_ref, false);
    f.ms.maps = msSince(t);
  }

  if (bounds && f.pose.ok) {
    t = Clock::now();
    if (stages_.boundary_use == BoundaryUse::Accumulate) {
      stages_.boundaries->accumulate(*scan, f.pose.ref, f.pose.t_ref);
    } else {
      f.boundary = stages_.boundaries->process(*scan, f.pose.ref, f.pose.t_ref);
    }
    f.ms.boundaries = msSince(t);
  }
  if (keep) f.scan = std::move(scan);
  totals_ += f.ms;
  return f;
}

std::vector<odometry::MapExclusion> movingExclusions(const objects::ObjectsFrame& f, double t_s,
                                                     const objects::TrackerParams& tp, double margin_m, double sweep_s,
                                                     double erase_back_s) {
  std::vector<odometry::MapExclusion> out;
  for (const objects::Track& tr : f.tracks) {
    if (!tr.moving) continue;
    odometry::MapExclusion b;
    b.stamp_s = t_s;
    b.centre_world = tr.x.head<2>();
    b.velocity_world_mps = tr.x.tail<2>();
    b.yaw_rad = tr.heading;
    b.half_length_m = 0.5 * std::max(tr.length, tp.car_length_m) + tr.speed() * sweep_s + margin_m;
    b.half_width_m = 0.5 * std::max(tr.width, tp.car_width_m) + margin_m;
    b.z_min_m = tr.z_min - margin_m, b.z_max_m = tr.z_max + margin_m;
    b.erase_back_s = erase_back_s;
    out.push_back(b);
  }
  return out;
}

std::unique_ptr<sources::ScanSource> openNonEmptySource(const std::string& path, const mrpt::config::CConfigFileBase& cfg,
                                                        const std::string& times_path) {
  auto src = sources::openScanSource(path, cfg, times_path);
  std::optional<Scan> first = src->next();
  if (!first) {
    const std::string err = src->errorMessage();
    throw std::runtime_error("input '" + path + "' gives no sweep" + (err.empty() ? "" : ": " + err));
  }
  return std::make_unique<PeekedSource>(std::move(src), std::move(*first));
}

}  // namespace roadslam::pipeline
