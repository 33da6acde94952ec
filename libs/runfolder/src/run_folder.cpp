#include "roadslam/runfolder/run_folder.h"

#include <filesystem>
#include <stdexcept>

namespace roadslam::runfolder {

RunFolder::RunFolder(std::string dir, const std::string& program)
    : dir_(std::move(dir)), manifest_(readManifest(dir_, program)) {}

bool RunFolder::has(const std::string& file) const { return std::filesystem::exists(path(file)); }

std::string RunFolder::need(const std::string& file) const {
  if (!has(file)) throw std::runtime_error(path(file) + ": missing from the " + manifest_.program + " folder");
  return path(file);
}

StampedTrajectory RunFolder::trajectory() const { return readTrajectory(need(kTrajectoryTum)); }
StampedTrajectory RunFolder::odometryTrajectory() const { return readTrajectory(need(kOdometryTum)); }
std::vector<FrameRow> RunFolder::frames() const { return readFramesCsv(need(kFramesCsv)); }
MapSummary RunFolder::mapSummary() const {
  const std::string p = need(kSummaryJson);
  return mapSummaryFromJson(readSummaryJson(p), p);
}
BoundsSummary RunFolder::boundsSummary() const {
  const std::string p = need(kSummaryJson);
  return boundsSummaryFromJson(readSummaryJson(p), p);
}
std::vector<LocalizationRow> RunFolder::localization() const { return readLocalizationCsv(need(kLocalizationCsv)); }
std::vector<ObjectRow> RunFolder::objects() const { return readObjectsCsv(need(kObjectsCsv)); }
std::vector<TrackRow> RunFolder::tracks() const { return readTracksCsv(need(kTracksCsv)); }
std::vector<EndedTrackRow> RunFolder::tracksEnded() const { return readTracksEndedCsv(need(kTracksEndedCsv)); }
std::vector<BoundaryRecord> RunFolder::boundaries() const { return readBoundariesJsonl(need(kBoundariesJsonl)); }

RunFolder openMapRun(const std::string& dir) { return RunFolder(dir, kMapProgram); }
RunFolder openBoundsRun(const std::string& dir) { return RunFolder(dir, kBoundsProgram); }

std::vector<long> trajectoryRowOfFrames(const std::vector<FrameRow>& frames, size_t trajectory_poses,
                                        const std::string& dir) {
  std::vector<long> out;
  long next = 0;
  for (const auto& f : frames) out.push_back(f.status == "skipped" ? -1 : next++);
  if (static_cast<size_t>(next) != trajectory_poses) {
    throw std::runtime_error(dir + "/" + kFramesCsv + ": " + std::to_string(next) + " sweeps with a pose, but " + dir +
                             "/" + kTrajectoryTum + " holds " + std::to_string(trajectory_poses) + " poses");
  }
  return out;
}

Manifest manifestFor(const std::string& program, const nlohmann::json& summary) {
  Manifest m;
  m.program = program;
  if (summary.contains("input") && summary["input"].is_string()) m.input = summary["input"].get<std::string>();
  if (summary.contains("input_id") && summary["input_id"].is_string()) m.input_id = summary["input_id"].get<std::string>();
  return m;
}

MapRunFiles mapRunOfTrajectory(const datasets::Trajectory& T_map_lidar, const std::string& input) {
  MapRunFiles f;
  f.trajectory = f.odometry = T_map_lidar;
  for (size_t i = 0; i < T_map_lidar.poses.size(); ++i) {
    FrameRow r;
    r.index = i, r.stamp_s = T_map_lidar.stamps_s.at(i), r.status = "ok", r.point_times = "none";
    const Eigen::Vector3d t = T_map_lidar.poses[i].translation();
    r.x_m = t.x(), r.y_m = t.y(), r.z_m = t.z();
    f.frames.push_back(r);
  }
  MapSummary s;
  s.frames = f.frames.size();
  if (s.frames) s.frames_by_status["ok"] = static_cast<int>(s.frames);
  s.complete = true;
  s.input = input;
  f.summary = mapSummaryJson(s);
  return f;
}

void writeMapTrajectories(const std::string& dir, const MapRunFiles& f) {
  datasets::writeTum(dir + "/" + kTrajectoryTum, f.trajectory);
  datasets::writeTum(dir + "/" + kOdometryTum, f.odometry);
  datasets::writeKittiPoses(dir + "/trajectory_kitti.txt", f.trajectory.poses);
  datasets::writeTimes(dir + "/trajectory_times.txt", f.trajectory.stamps_s);
  writeFramesCsv(dir + "/" + kFramesCsv, f.frames);
}

void writeMapRunEnd(const std::string& dir, const nlohmann::json& summary) {
  writeSummaryJson(dir + "/" + kSummaryJson, summary);
  writeManifest(dir, manifestFor(kMapProgram, summary));
}

void writeMapRun(const std::string& dir, const MapRunFiles& f) {
  writeMapTrajectories(dir, f);
  writeMapRunEnd(dir, f.summary);
}

}  // namespace roadslam::runfolder
