// roadslam-map's summary for a person; summary.json (and --json) hold every field.
#include <algorithm>
#include <string>

#include "lidar_model_json.h"
#include "roadslam/common/text_summary.h"
#include "roadslam/jobs/map_job.h"

namespace roadslam::jobs {
namespace {

int statusCount(const nlohmann::json& s, const char* status) {
  return s.contains("frames_by_status") ? s["frames_by_status"].value(status, 0) : 0;
}

}  // namespace

std::string summaryText(const nlohmann::json& s, const std::string& out_dir) {
  SummaryLines lines;
  lines.emplace_back("input", s.value("input", std::string("?")));
  if (s.contains("lidar_model")) lines.emplace_back("lidar model", lidarModelText(s));
  std::string by_status;
  if (s.contains("frames_by_status")) {
    for (const auto& [k, v] : s["frames_by_status"].items()) {
      by_status += (by_status.empty() ? "" : ", ") + k + " " + std::to_string(v.get<int>());
    }
  }
  lines.emplace_back("frames", std::to_string(s.value("frames", 0)) + (by_status.empty() ? "" : " (" + by_status + ")") +
                                   (s.value("interrupted", false) ? ", interrupted" : ""));
  lines.emplace_back("failed", formatText("%d (not converged or empty), %d degenerate", s.value("failed_frames", 0),
                                          statusCount(s, "degenerate")));
  lines.emplace_back("distance", formatText("%.1f m", s.value("distance_m", 0.0)));
  lines.emplace_back("duration", formatText("%.1f s of recording, %.1f s wall time", s.value("duration_s", 0.0),
                                            s.value("wall_time_s", 0.0)));
  lines.emplace_back("ms per frame", formatText("%.1f mean, %.1f p95, %.1f max", s.value("ms_per_frame_mean", 0.0),
                                                s.value("ms_per_frame_p95", 0.0), s.value("ms_per_frame_max", 0.0)));
  lines.emplace_back("loop closures", formatText("%d (%d candidates rejected)", s.value("loop_closures", 0),
                                                 s.value("loop_candidates_rejected", 0)));
  if (s.contains("objects")) {
    const auto& o = s["objects"];
    const double frames = std::max(1, s.value("frames", 0));
    lines.emplace_back("objects", formatText("%.1f per sweep, %.2f ms per sweep (segmentation + tracking), %zu moving points kept out of the maps",
                                             o.value("objects", 0) / frames, o["ms_segment_track_per_frame"].value("mean", 0.0),
                                             o.value("moving_points_removed_from_maps", size_t{0})));
  }
  if (s.contains("can")) {
    const auto& c = s["can"];
    lines.emplace_back("CAN prior", formatText("%d priors used, %d missing", c.value("priors_used", 0),
                                               c.value("priors_missing", 0)));
  }
  if (s.contains("gnss")) {
    const auto& g = s["gnss"];
    lines.emplace_back("GNSS", g.value("status", std::string("?")) == "ok"
                                   ? formatText("%zu fixes: %zu used, %zu rejected, %zu outside the drive; %.2f m rms residual",
                                                g.value("fixes", size_t{0}), g.value("fixes_used", size_t{0}),
                                                g.value("fixes_rejected", size_t{0}), g.value("fixes_unmatched", size_t{0}),
                                                g.value("rms_horizontal_residual_m", 0.0))
                                   : "not fused: " + g.value("status", std::string("?")));
  }
  lines.emplace_back("warnings", warningsValue(s.contains("warnings") ? s["warnings"].size() : 0));
  if (s.contains("write_errors") && !s["write_errors"].empty())
    lines.emplace_back("write errors", std::to_string(s["write_errors"].size()) + " outputs not written (on stderr, summary.json write_errors)");
  lines.emplace_back("outputs", out_dir + " (trajectory.tum, maps, frames.csv, summary.json)");
  return alignedLines(lines);
}

}  // namespace roadslam::jobs
