#pragma once
// summary.json's LiDAR model keys, shared by roadslam-map's and roadslam-bounds' summaries.
#include <nlohmann/json.hpp>

#include "roadslam/sources/scan_source.h"

namespace roadslam::jobs {

/// lidar_model, lidar_model_source and lidar_layout (docs/run-folder.md) of \p source into \p summary;
/// nothing for a source of points that decodes no packets (a KITTI folder).
inline void addLidarModel(nlohmann::json& summary, const sources::ScanSource& source) {
  const auto m = source.lidarModel();
  if (!m) return;
  summary["lidar_model"] = m->model;
  summary["lidar_model_source"] = m->source;
  summary["lidar_layout"] = m->layout;
}

/// "VLP-16 (by packet layout)" for the text summaries; empty without the keys.
inline std::string lidarModelText(const nlohmann::json& summary) {
  if (!summary.contains("lidar_model")) return "";
  return summary.value("lidar_model", std::string("?")) + " (by " + summary.value("lidar_model_source", std::string("?")) +
         ")";
}

}  // namespace roadslam::jobs
