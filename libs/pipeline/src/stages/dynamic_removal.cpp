#include "roadslam/pipeline/stages/dynamic_removal.h"

#include "roadslam/objects/stage.h"
#include "roadslam/objects/track_box.h"

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
    b.box = objects::movingTrackBox(tr, tp, sweep_s).grown(margin_m);
    b.velocity_world_mps = tr.x.tail<2>();
    b.erase_back_s = erase_back_s;
    out.push_back(b);
  }
  return out;
}

}  // namespace roadslam::pipeline
