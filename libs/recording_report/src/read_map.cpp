// The map part of the report: a roadslam-map output folder's trajectory, pictures and summary figures.
#include <cmath>
#include <filesystem>

#include "internal.h"
#include "roadslam/runfolder/run_folder.h"

namespace fs = std::filesystem;

namespace roadslam::recording_report {

MapReport readMap(const std::string& dir, const ReportParams& p) {
  const runfolder::RunFolder run = runfolder::openMapRun(dir);  // throws naming run.json for a foreign folder
  const runfolder::StampedTrajectory traj = run.trajectory();
  MapReport m;
  m.dir = dir;
  std::vector<double> x, y;
  for (size_t i = 0; i < traj.size(); ++i) {
    const Eigen::Vector3d t = traj.pose(i).translation();
    if (!x.empty()) m.length_m += std::hypot(t.x() - x.back(), t.y() - y.back());
    x.push_back(t.x());
    y.push_back(t.y());
  }
  m.poses = x.size();
  m.x_m = decimate(x, p.max_plot_points);
  m.y_m = decimate(y, p.max_plot_points);
  for (const char* pic : {"map_top.png", "grid.png"})
    if (fs::exists(dir + "/" + pic)) m.pictures.push_back(dir + "/" + pic);
  const runfolder::MapSummary s = run.mapSummary();
  m.summary["frames"] = s.frames;
  m.summary["keyframes"] = s.keyframes;
  m.summary["failed_frames"] = s.failed_frames;
  if (s.loop_closures) m.summary["loop_closures"] = *s.loop_closures;
  m.summary["ms_per_frame_p50"] = s.ms_per_frame_p50;
  m.summary["ms_per_frame_p95"] = s.ms_per_frame_p95;
  return m;
}

}  // namespace roadslam::recording_report
