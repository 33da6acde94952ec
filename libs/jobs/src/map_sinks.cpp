#include "map_sinks.h"

#include <algorithm>

#include "roadslam/common/atomic_file.h"

namespace roadslam::jobs {

void ObjectsOutput::add(const pipeline::PipelineFrame& f, objects::ObjectsStage& stage) {
  if (!f.objects) return;
  moving_points_removed += f.moving_points_removed;
  retro_points_removed += f.retro_points_removed;
  if (f.pose.odometry) odometry_points_excluded += static_cast<size_t>(f.pose.odometry->map_points_excluded);
  const objects::ObjectsFrame& o = *f.objects;
  const double t = f.pose.ok ? f.pose.t_ref : f.pose.stamp_s;  // the time the tracks are at
  if (f.pose.ok) {
    objects += objects::objectsCsvRows(f.index, t, f.pose.ref, o);
    ms.push_back(o.ms_segment + o.ms_track);
    ms_ground.push_back(o.ms_ground);
    n_objects += o.objects.size();
  }
  tracks += objects::tracksCsvRows(f.index, t, o);
  for (const objects::Track& tr : o.tracks) {
    if (tr.moving) last_moving[tr.id] = {tr.id, tr.box(), tr.x.tail<2>()};
  }
  takeEnded(stage);
}

void ObjectsOutput::takeEnded(objects::ObjectsStage& stage) {
  const auto e = stage.tracker().takeEnded();
  for (const auto& t : e) end_reasons[t.reason]++;
  ended += objects::endedCsvRows(e);
}

nlohmann::json ObjectsOutput::summary(const objects::ObjectsStage& stage) const {
  auto stats = [](std::vector<double> v) {
    if (v.empty()) return nlohmann::json{{"mean", 0}, {"p95", 0}, {"max", 0}};
    double sum = 0;
    for (double x : v) sum += x;
    std::sort(v.begin(), v.end());
    return nlohmann::json{{"mean", sum / v.size()}, {"p95", v[std::min(v.size() - 1, v.size() * 95 / 100)]},
                          {"max", v.back()}};
  };
  int confirmed_alive = 0;
  for (const auto& t : stage.tracker().tracks()) confirmed_alive += t.state == objects::TrackState::Confirmed;
  return {{"objects", n_objects},
          {"tracks_alive_at_end", confirmed_alive},
          {"moving_points_removed_from_maps", moving_points_removed},
          {"earlier_points_removed_from_keyframes", retro_points_removed},
          {"moving_points_kept_out_of_odometry_map", odometry_points_excluded},
          {"tracks_ended", end_reasons},
          {"tracks_reidentified", stage.tracker().reidentified()},
          {"ms_segment_track_per_frame", stats(ms)},
          {"ms_ground_per_frame", stats(ms_ground)}};
}

void ObjectsOutput::write(const std::string& out_dir) const {
  writeFileAtomically(out_dir + "/objects.csv", objects);
  writeFileAtomically(out_dir + "/tracks.csv", tracks);
  writeFileAtomically(out_dir + "/tracks_ended.csv", ended);
}

void LocalizationOutput::add(const pipeline::PipelineFrame& f) {
  const localization::LocalizationResult& r = *f.localization;
  localized.push_back(r.status != localization::LocalizationStatus::Lost ? 1 : 0);
  T_map_lidar.push_back(r.T_map_lidar);
  tracked += r.status == localization::LocalizationStatus::Tracked;
  relocalized += r.status == localization::LocalizationStatus::Relocalized;
  lost += r.status == localization::LocalizationStatus::Lost;
  sum_conf += r.confidence;
  csv += runfolder::localizationCsvRow(
      {f.index, f.pose.stamp_s, localization::toString(r.status), r.confidence, r.keyframe, r.weak_directions, r.reason});
}

void LocalizationOutput::bridge(const std::vector<odometry::FrameResult>& frames) {
  const size_t n = std::min(frames.size(), T_map_lidar.size());
  long prev = -1;
  std::vector<long> next(n, -1);
  for (long i = static_cast<long>(n) - 1, nx = -1; i >= 0; --i) {
    if (localized[static_cast<size_t>(i)]) nx = i;
    next[static_cast<size_t>(i)] = nx;
  }
  for (size_t i = 0; i < n; ++i) {
    if (localized[i]) {
      prev = static_cast<long>(i);
      continue;
    }
    const long k = prev >= 0 ? prev : next[i];
    if (k < 0) {
      T_map_lidar[i] = frames[i].T_world_lidar;
      continue;
    }
    const auto ku = static_cast<size_t>(k);
    T_map_lidar[i] = T_map_lidar[ku] * frames[ku].T_world_lidar.inverse() * frames[i].T_world_lidar;
  }
  T_map_lidar.resize(frames.size(), Eigen::Isometry3d::Identity());
}

nlohmann::json LocalizationOutput::summary(const std::string& dir, size_t map_points) const {
  const int n = tracked + relocalized + lost;
  return {{"prior_map", dir},       {"map_points", map_points}, {"tracked", tracked},
          {"relocalized", relocalized}, {"lost", lost},       {"mean_confidence", n > 0 ? sum_conf / n : 0.0}};
}

}  // namespace roadslam::jobs
