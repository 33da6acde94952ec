#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>

#include "roadslam/common/atomic_file.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/pipeline/map_job.h"

namespace roadslam::pipeline {
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

std::string framesCsv(const std::vector<odometry::FrameResult>& frames) {
  std::ostringstream os;
  os << "index,stamp_s,status,point_times,deskewed,keyframe,x_m,y_m,z_m,points_in,points_registered,iterations,inliers,"
        "fitness_m,threshold_m,weak_directions,motion_information,ms_preprocess,ms_register,ms_map,ms_total,reason\n";
  char buf[512];
  for (const auto& f : frames) {
    const auto t = f.T_world_lidar.translation();
    std::snprintf(buf, sizeof buf, "%zu,%.6f,%s,%s,%d,%d,%.4f,%.4f,%.4f,%d,%d,%d,%d,%.4f,%.3f,%d,%.5f,%.3f,%.3f,%.3f,%.3f,",
                  f.index, f.stamp_s, odometry::toString(f.status), f.point_times, f.deskewed ? 1 : 0,
                  f.keyframe ? 1 : 0, t.x(), t.y(), t.z(),
                  f.points_in, f.points_registered, f.iterations, f.inliers, f.fitness_m, f.threshold_m,
                  f.weak_directions, f.motion_information, f.ms_preprocess, f.ms_register, f.ms_map, f.ms_total);
    std::string reason = f.reason;
    std::replace(reason.begin(), reason.end(), ',', ';');
    os << buf << reason << "\n";
  }
  return os.str();
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

void writeMapOutputs(const std::string& out_dir, const std::vector<odometry::FrameResult>& frames,
                     const std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>& T_map_lidar,
                     const nlohmann::json& summary) {
  datasets::Trajectory traj, odom;
  for (size_t i = 0; i < frames.size(); ++i) {
    const auto& f = frames[i];
    if (!hasPose(f)) continue;
    traj.stamps_s.push_back(f.stamp_s);
    traj.poses.push_back(T_map_lidar.empty() ? f.T_world_lidar : T_map_lidar.at(i));
    odom.stamps_s.push_back(f.stamp_s);
    odom.poses.push_back(f.T_world_lidar);
  }
  datasets::writeTum(out_dir + "/trajectory.tum", traj);
  datasets::writeTum(out_dir + "/trajectory_odometry.tum", odom);
  datasets::writeKittiPoses(out_dir + "/trajectory_kitti.txt", traj.poses);
  datasets::writeTimes(out_dir + "/trajectory_times.txt", traj.stamps_s);
  writeFileAtomically(out_dir + "/frames.csv", framesCsv(frames));
  writeFileAtomically(out_dir + "/summary.json", summary.dump(2) + "\n");
}

}  // namespace roadslam::pipeline
