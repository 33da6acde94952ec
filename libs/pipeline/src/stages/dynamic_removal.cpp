#include "roadslam/pipeline/stages/dynamic_removal.h"

#include <algorithm>

#include "roadslam/objects/stage.h"

namespace roadslam::pipeline {

void DynamicRemovalStage::process(PipelineFrame& f) {
  if (!f.objects) return;
  if (p_.from_odometry) {
    const double t_tracks = f.pose.ok ? f.pose.t_ref : f.pose.stamp_s;  // the time the tracks are at
    poses_.excludeFromMap(movingExclusions(*f.objects, t_tracks, tracking_, p_.margin_m, 0.1, p_.odometry_erase_back_s));
  }
  if (p_.from_maps && f.pose.ok && f.pose.points_lidar) {
    std::vector<Eigen::Vector3d> pts = *f.pose.points_lidar;
    f.moving_points_removed = objects::removeMovingPoints(pts, *f.objects, p_.margin_m, f.pose.ref);
    f.map_points_lidar = std::move(pts);
    f.keyframe_erasure = KeyframeErasure{f.objects->retro, p_.margin_m};
  }
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

}  // namespace roadslam::pipeline
