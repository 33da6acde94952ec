#include <algorithm>
#include <map>

#include "roadslam/jobs/map_job.h"
#include "roadslam/runfolder/run_folder.h"

namespace roadslam::jobs {
namespace {

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t i = std::min(v.size() - 1, static_cast<size_t>(q * (v.size() - 1) + 0.5));
  return v[i];
}

bool hasPose(const odometry::FrameResult& f) {
  return f.status != odometry::FrameStatus::Skipped;
}

runfolder::FrameRow frameRow(const odometry::FrameResult& f) {
  runfolder::FrameRow r;
  const auto t = f.T_world_lidar.translation();
  r.index = f.index, r.stamp_s = f.stamp_s, r.status = odometry::toString(f.status), r.point_times = f.point_times;
  r.deskewed = f.deskewed, r.keyframe = f.keyframe, r.x_m = t.x(), r.y_m = t.y(), r.z_m = t.z();
  r.points_in = f.points_in, r.points_registered = f.points_registered, r.iterations = f.iterations, r.inliers = f.inliers;
  r.fitness_m = f.fitness_m, r.threshold_m = f.threshold_m, r.weak_directions = f.weak_directions;
  r.motion_information = f.motion_information;
  r.ms_preprocess = f.ms_preprocess, r.ms_register = f.ms_register, r.ms_map = f.ms_map, r.ms_total = f.ms_total;
  r.reason = f.reason;
  return r;
}

/// How much of the drive the scans could not see the motion in (FrameStatus::Degenerate): the count,
/// its fraction of the frames with a pose, and the longest run of consecutive degenerate frames, in
/// frames and in seconds from the last frame before it (the motion over that span was predicted).
nlohmann::json blindness(const std::vector<odometry::FrameResult>& frames) {
  int degenerate = 0, posed = 0, run = 0, longest = 0;
  double longest_s = 0, longest_start_s = 0;
  const odometry::FrameResult* before_run = nullptr;
  const odometry::FrameResult* prev = nullptr;
  for (const auto& f : frames) {
    if (!hasPose(f)) continue;
    ++posed;
    if (f.status == odometry::FrameStatus::Degenerate) {
      ++degenerate;
      if (run++ == 0) before_run = prev;
      const double span_s = f.stamp_s - (before_run ? before_run->stamp_s : f.stamp_s);
      if (run > longest) {
        longest = run;
        longest_s = span_s;
        longest_start_s = before_run ? before_run->stamp_s : f.stamp_s;
      }
    } else {
      run = 0;
    }
    prev = &f;
  }
  nlohmann::json j;
  j["degenerate_frames"] = degenerate;
  j["degenerate_fraction"] = posed ? static_cast<double>(degenerate) / posed : 0.0;
  j["longest_blind_frames"] = longest;
  j["longest_blind_s"] = longest_s;
  j["longest_blind_start_s"] = longest_start_s;
  return j;
}

}  // namespace

nlohmann::json summarize(const std::vector<odometry::FrameResult>& frames) {
  nlohmann::json j;
  std::map<std::string, int> by_status, reasons;
  std::vector<double> ms;
  int keyframes = 0, failed = 0;
  std::map<std::string, int> timed_by;
  int deskewed = 0;
  for (const auto& f : frames) {
    if (hasPose(f)) {
      ++timed_by[f.point_times];
      deskewed += f.deskewed ? 1 : 0;
    }
    ++by_status[odometry::toString(f.status)];
    if (f.keyframe) ++keyframes;
    if (f.status == odometry::FrameStatus::NotConverged || f.status == odometry::FrameStatus::Empty) {
      ++failed;
      ++reasons[f.reason.empty() ? odometry::toString(f.status) : f.reason.substr(0, f.reason.find(':'))];
    }
    if (hasPose(f)) ms.push_back(f.ms_total);
  }
  double mean = 0;
  for (double v : ms) mean += v;
  j["frames"] = frames.size();
  j["keyframes"] = keyframes;
  j["failed_frames"] = failed;
  j["failure_reasons"] = reasons;
  j["point_times"] = timed_by;
  j["deskewed_frames"] = deskewed;
  j["frames_by_status"] = by_status;
  j["blind"] = blindness(frames);
  j["ms_per_frame_mean"] = ms.empty() ? 0.0 : mean / ms.size();
  j["ms_per_frame_p50"] = percentile(ms, 0.5);
  j["ms_per_frame_p95"] = percentile(ms, 0.95);
  j["ms_per_frame_max"] = ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end());
  if (!frames.empty()) {
    double dist = 0;
    const odometry::FrameResult* prev = nullptr;
    for (const auto& f : frames) {
      if (!hasPose(f)) continue;
      if (prev) dist += (f.T_world_lidar.translation() - prev->T_world_lidar.translation()).norm();
      prev = &f;
    }
    j["distance_m"] = dist;
    j["duration_s"] = frames.back().stamp_s - frames.front().stamp_s;
  }
  return j;
}

runfolder::MapRunFiles mapRunFiles(const std::vector<odometry::FrameResult>& frames, const mapping::PoseVector& T_map_lidar) {
  runfolder::MapRunFiles out;
  for (size_t i = 0; i < frames.size(); ++i) {
    const auto& f = frames[i];
    out.frames.push_back(frameRow(f));
    if (!hasPose(f)) continue;
    out.trajectory.stamps_s.push_back(f.stamp_s);
    out.trajectory.poses.push_back(T_map_lidar.empty() ? f.T_world_lidar : T_map_lidar.at(i));
    out.odometry.stamps_s.push_back(f.stamp_s);
    out.odometry.poses.push_back(f.T_world_lidar);
  }
  return out;
}

void writeMapOutputs(const std::string& out_dir, const std::vector<odometry::FrameResult>& frames,
                     const std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>& T_map_lidar,
                     const nlohmann::json& summary) {
  runfolder::MapRunFiles out = mapRunFiles(frames, T_map_lidar);
  out.summary = summary;
  runfolder::writeMapRun(out_dir, out);
}

}  // namespace roadslam::jobs
