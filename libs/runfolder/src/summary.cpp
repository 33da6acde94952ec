#include "roadslam/runfolder/summary.h"

#include <fstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"

namespace roadslam::runfolder {
namespace {

/// j[key] as T; throws naming \p what and the key.
template <class T>
T need(const nlohmann::json& j, const char* key, const std::string& what) {
  if (!j.is_object() || !j.contains(key)) throw std::runtime_error(what + ": no key '" + key + "'");
  try {
    return j.at(key).get<T>();
  } catch (const std::exception& e) {
    throw std::runtime_error(what + ": key '" + key + "': " + e.what());
  }
}
template <class T>
T maybe(const nlohmann::json& j, const char* key, const T& otherwise, const std::string& what) {
  return j.contains(key) ? need<T>(j, key, what) : otherwise;
}

std::vector<LoopRecord> loops(const nlohmann::json& a, const std::string& what) {
  std::vector<LoopRecord> out;
  for (const auto& l : a) {
    LoopRecord r;
    r.query_frame = need<size_t>(l, "query_frame", what), r.match_frame = need<size_t>(l, "match_frame", what);
    r.query_keyframe = need<size_t>(l, "query_keyframe", what), r.match_keyframe = need<size_t>(l, "match_keyframe", what);
    r.fitness_m = need<double>(l, "fitness_m", what), r.overlap = need<double>(l, "overlap", what);
    r.correction_m = need<double>(l, "correction_m", what);
    r.reason = maybe<std::string>(l, "reason", "", what);
    out.push_back(r);
  }
  return out;
}

}  // namespace

int MapSummary::byStatus(const std::string& status) const {
  const auto it = frames_by_status.find(status);
  return it == frames_by_status.end() ? 0 : it->second;
}

MapSummary mapSummaryFromJson(const nlohmann::json& j, const std::string& what) {
  MapSummary s;
  s.json = j;
  s.frames = need<size_t>(j, "frames", what);
  s.keyframes = need<size_t>(j, "keyframes", what);
  s.failed_frames = need<size_t>(j, "failed_frames", what);
  s.frames_by_status = need<std::map<std::string, int>>(j, "frames_by_status", what);
  s.ms_per_frame_mean = need<double>(j, "ms_per_frame_mean", what);
  s.ms_per_frame_p50 = need<double>(j, "ms_per_frame_p50", what);
  s.ms_per_frame_p95 = need<double>(j, "ms_per_frame_p95", what);
  s.ms_per_frame_max = need<double>(j, "ms_per_frame_max", what);
  s.distance_m = maybe<double>(j, "distance_m", 0.0, what);
  s.duration_s = maybe<double>(j, "duration_s", 0.0, what);
  if (j.contains("loop_closures")) s.loop_closures = need<size_t>(j, "loop_closures", what);
  if (j.contains("loop_candidates_rejected")) s.loop_candidates_rejected = need<size_t>(j, "loop_candidates_rejected", what);
  if (j.contains("loops")) {
    s.loops_accepted = loops(need<nlohmann::json>(j["loops"], "accepted", what + " loops"), what + " loops accepted");
    s.loops_rejected = loops(need<nlohmann::json>(j["loops"], "rejected", what + " loops"), what + " loops rejected");
  }
  s.complete = need<bool>(j, "complete", what);
  s.interrupted = maybe<bool>(j, "interrupted", false, what);
  s.warnings = need<std::vector<std::string>>(j, "warnings", what);
  s.input = maybe<std::string>(j, "input", "", what);
  s.lidar_model = maybe<std::string>(j, "lidar_model", "", what);
  s.lidar_model_source = maybe<std::string>(j, "lidar_model_source", "", what);
  return s;
}

BoundsSummary boundsSummaryFromJson(const nlohmann::json& j, const std::string& what) {
  BoundsSummary s;
  s.json = j;
  s.frames = need<size_t>(j, "frames", what);
  s.frames_without_pose = need<size_t>(j, "frames_without_pose", what);
  s.left_found_rate = need<double>(j, "left_found_rate", what);
  s.right_found_rate = need<double>(j, "right_found_rate", what);
  s.both_found_rate = need<double>(j, "both_found_rate", what);
  s.ms_per_frame_mean = need<double>(j, "ms_per_frame_mean", what);
  s.ms_per_frame_max = need<double>(j, "ms_per_frame_max", what);
  s.mode = need<std::string>(j, "mode", what);
  s.poses = maybe<std::string>(j, "poses", "", what);
  s.complete = need<bool>(j, "complete", what);
  s.warnings = need<std::vector<std::string>>(j, "warnings", what);
  s.input = maybe<std::string>(j, "input", "", what);
  s.lidar_model = maybe<std::string>(j, "lidar_model", "", what);
  s.lidar_model_source = maybe<std::string>(j, "lidar_model_source", "", what);
  return s;
}

nlohmann::json mapSummaryJson(const MapSummary& s) {
  nlohmann::json j = s.json.is_object() ? s.json : nlohmann::json::object();
  j["frames"] = s.frames, j["keyframes"] = s.keyframes, j["failed_frames"] = s.failed_frames;
  j["frames_by_status"] = s.frames_by_status;
  j["ms_per_frame_mean"] = s.ms_per_frame_mean, j["ms_per_frame_p50"] = s.ms_per_frame_p50;
  j["ms_per_frame_p95"] = s.ms_per_frame_p95, j["ms_per_frame_max"] = s.ms_per_frame_max;
  j["distance_m"] = s.distance_m, j["duration_s"] = s.duration_s;
  auto loops = [](const std::vector<LoopRecord>& v) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& l : v)
      a.push_back({{"query_frame", l.query_frame}, {"match_frame", l.match_frame}, {"query_keyframe", l.query_keyframe},
                   {"match_keyframe", l.match_keyframe}, {"fitness_m", l.fitness_m}, {"overlap", l.overlap},
                   {"correction_m", l.correction_m}, {"reason", l.reason}});
    return a;
  };
  if (s.loop_closures || !s.loops_accepted.empty() || !s.loops_rejected.empty()) {
    j["loop_closures"] = s.loop_closures.value_or(s.loops_accepted.size());
    j["loop_candidates_rejected"] = s.loop_candidates_rejected.value_or(s.loops_rejected.size());
    j["loops"] = {{"accepted", loops(s.loops_accepted)}, {"rejected", loops(s.loops_rejected)}};
  }
  j["complete"] = s.complete, j["interrupted"] = s.interrupted, j["warnings"] = s.warnings, j["input"] = s.input;
  if (!s.lidar_model.empty()) j["lidar_model"] = s.lidar_model, j["lidar_model_source"] = s.lidar_model_source;
  return j;
}

void writeSummaryJson(const std::string& path, const nlohmann::json& summary) {
  writeFileAtomically(path, summary.dump(2) + "\n");
}

nlohmann::json readSummaryJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace roadslam::runfolder
