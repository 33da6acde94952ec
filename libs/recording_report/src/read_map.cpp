// The map part of the report: a roadslam-map output folder's trajectory, pictures and summary figures.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "internal.h"

namespace fs = std::filesystem;

namespace roadslam::recording_report {

MapReport readMap(const std::string& dir, const ReportParams& p) {
  if (!fs::is_directory(dir)) throw std::runtime_error(dir + ": not a folder (--map wants a roadslam-map output folder)");
  const std::string tum = dir + "/trajectory.tum";
  std::ifstream in(tum);
  if (!in) throw std::runtime_error(tum + ": cannot be read (not a roadslam-map output folder?)");
  MapReport m;
  m.dir = dir;
  std::vector<double> x, y;
  std::string line;
  for (size_t n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    double v[8];
    for (double& d : v)
      if (!(ls >> d)) throw std::runtime_error(tum + ":" + std::to_string(n) + ": expected 't x y z qx qy qz qw'");
    if (!x.empty()) m.length_m += std::hypot(v[1] - x.back(), v[2] - y.back());
    x.push_back(v[1]);
    y.push_back(v[2]);
  }
  m.poses = x.size();
  m.x_m = decimate(x, p.max_plot_points);
  m.y_m = decimate(y, p.max_plot_points);
  for (const char* pic : {"map_top.png", "grid.png"})
    if (fs::exists(dir + "/" + pic)) m.pictures.push_back(dir + "/" + pic);
  std::ifstream js(dir + "/summary.json");
  if (js) {
    try {
      const auto all = nlohmann::json::parse(js);
      for (const char* k : {"frames", "keyframes", "failed_frames", "loop_closures", "ms_per_frame_p50", "ms_per_frame_p95"})
        if (all.contains(k)) m.summary[k] = all[k];
    } catch (const std::exception& e) {
      throw std::runtime_error(dir + "/summary.json: " + e.what());
    }
  }
  return m;
}

}  // namespace roadslam::recording_report
