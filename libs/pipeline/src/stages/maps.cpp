#include "roadslam/pipeline/stages/maps.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roadslam::pipeline {
namespace {
// a box applies to the keyframe within half a sweep (10 Hz) of its time
constexpr double kErasureMatch_s = 0.049;
}  // namespace

MapsStage::MapsStage(const mapping::MapperParams& mapper, std::unique_ptr<mapping::OctoMapWorker> octomap,
                     const MapsStageParams& p)
    : mapper_(mapper), octomap_(std::move(octomap)), p_(p) {}

MapsStage::~MapsStage() = default;

void MapsStage::process(PipelineFrame& f) {
  if (!f.pose.odometry || !f.pose.points_lidar) throw std::logic_error("Pipeline: the maps stage needs the odometry's poses");
  std::optional<mapping::WheelMotion> wheel;
  if (f.pose.T_baseprev_basecurr) wheel = mapping::WheelMotion{*f.pose.T_baseprev_basecurr, f.pose.T_base_lidar};
  f.loop_closed = mapper_.addFrame(*f.pose.odometry, f.map_points_lidar ? *f.map_points_lidar : *f.pose.points_lidar, wheel);
  if (f.keyframe_erasure) f.retro_points_removed = eraseFromKeyframes(*f.keyframe_erasure);
  feedOctoMap(f.loop_closed, f.pose.t_ref, false);
}

/// Keyframes go to the OctoMap once older than octomap_delay_s (every keyframe when \p flush); after a
/// loop, the OctoMap is rebuilt from the keyframes decided on so far at their moved poses.
void MapsStage::feedOctoMap(bool loop, double now_s, bool flush) {
  if (!octomap_) return;
  const auto& kfs = mapper_.keyframes();
  const double spacing = p_.octomap_keyframe_spacing_m;
  if (loop) {
    mapping::PoseVector poses = mapper_.keyframePoses();
    poses.resize(std::min(poses.size(), octo_seen_));
    octomap_->rebuild(mapping::octoMapItems(kfs, poses, spacing));
  }
  for (; octo_seen_ < kfs.size() && (flush || kfs[octo_seen_].stamp_s <= now_s - p_.octomap_delay_s); ++octo_seen_) {
    if (mapping::takesOctoMap(kfs, octo_seen_, spacing)) {
      octomap_->push({kfs[octo_seen_].points_lidar, mapper_.graph().pose(octo_seen_)});
    }
  }
}

/// Drops from the keyframes the points inside the boxes (map frame, grown by the margin) of the
/// keyframes made at the boxes' times (a keyframe's stamp is its odometry frame's, the objects' time).
size_t MapsStage::eraseFromKeyframes(const KeyframeErasure& e) {
  if (e.boxes.empty()) return 0;
  const auto& kfs = mapper_.keyframes();
  double t_first = e.boxes.front().t;
  for (const auto& b : e.boxes) t_first = std::min(t_first, b.t);
  size_t removed = 0;
  for (size_t k = kfs.size(); k-- > 0 && kfs[k].stamp_s >= t_first - kErasureMatch_s;) {
    const Eigen::Isometry3d T_odom_lidar = kfs[k].T_odom_lidar;
    std::vector<const objects::BoxRecord*> here;
    for (const auto& b : e.boxes) {
      if (std::abs(b.t - kfs[k].stamp_s) < kErasureMatch_s) here.push_back(&b);
    }
    if (here.empty()) continue;
    removed += mapper_.erasePoints(k, [&](const Eigen::Vector3f& q) {
      const Eigen::Vector3d p_map = T_odom_lidar * q.cast<double>();
      for (const auto* b : here) {
        if (b->box.contains(p_map, e.margin_m)) return true;
      }
      return false;
    });
  }
  return removed;
}

}  // namespace roadslam::pipeline
