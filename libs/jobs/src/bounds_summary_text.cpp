// roadslam-bounds' summary for a person; summary.json (and --json) hold every field.
#include <string>

#include "roadslam/jobs/bounds_job.h"
#include "lidar_model_json.h"
#include "roadslam/common/text_summary.h"

namespace roadslam::jobs {

std::string boundsSummaryText(const nlohmann::json& s, const std::string& out_dir) {
  SummaryLines lines;
  lines.emplace_back("input", s.value("input", std::string("?")));
  if (s.contains("lidar_model")) lines.emplace_back("lidar model", lidarModelText(s));
  lines.emplace_back("mode", s.value("mode", std::string("?")) + ", poses from " + s.value("poses", std::string("?")));
  lines.emplace_back("frames", formatText("%d (%d without a pose)", s.value("frames", 0), s.value("frames_without_pose", 0)));
  lines.emplace_back("found", formatText("left %.1f %%, right %.1f %%, both %.1f %% of the frames",
                                         100.0 * s.value("left_found_rate", 0.0), 100.0 * s.value("right_found_rate", 0.0),
                                         100.0 * s.value("both_found_rate", 0.0)));
  lines.emplace_back("ms per frame", formatText("%.1f mean, %.1f max (detector only)", s.value("ms_per_frame_mean", 0.0),
                                                s.value("ms_per_frame_max", 0.0)));
  lines.emplace_back("warnings", warningsValue(s.contains("warnings") ? s["warnings"].size() : 0));
  lines.emplace_back("outputs", out_dir + " (boundaries.jsonl, frames/, summary.json)");
  return alignedLines(lines);
}

}  // namespace roadslam::jobs
