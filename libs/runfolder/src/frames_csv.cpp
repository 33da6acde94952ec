#include "roadslam/runfolder/frames_csv.h"

#include "roadslam/common/atomic_file.h"
#include "roadslam/runfolder/csv.h"

namespace roadslam::runfolder {
namespace {
const std::vector<std::string> kColumns = {
    "index", "stamp_s", "status", "point_times", "deskewed", "keyframe", "x_m", "y_m", "z_m", "points_in",
    "points_registered", "iterations", "inliers", "fitness_m", "threshold_m", "weak_directions", "motion_information",
    "ms_preprocess", "ms_register", "ms_map", "ms_total", "reason"};
}  // namespace

std::string framesCsvHeader() {
  std::string h;
  for (const auto& c : kColumns) h += (h.empty() ? "" : ",") + c;
  return h + "\n";
}

std::string framesCsvRow(const FrameRow& f) {
  return format("%zu,%.6f,%s,%s,%d,%d,%.4f,%.4f,%.4f,%d,%d,%d,%d,%.4f,%.3f,%d,%.5f,%.3f,%.3f,%.3f,%.3f,", f.index,
                f.stamp_s, f.status.c_str(), f.point_times.c_str(), f.deskewed ? 1 : 0, f.keyframe ? 1 : 0, f.x_m, f.y_m,
                f.z_m, f.points_in, f.points_registered, f.iterations, f.inliers, f.fitness_m, f.threshold_m,
                f.weak_directions, f.motion_information, f.ms_preprocess, f.ms_register, f.ms_map, f.ms_total) +
         csvText(f.reason) + "\n";
}

void writeFramesCsv(const std::string& path, const std::vector<FrameRow>& rows) {
  std::string out = framesCsvHeader();
  for (const auto& r : rows) out += framesCsvRow(r);
  writeFileAtomically(path, out);
}

std::vector<FrameRow> readFramesCsv(const std::string& path) {
  std::vector<FrameRow> rows;
  for (CsvReader c(path, kColumns); c.next();) {
    FrameRow f;
    f.index = static_cast<size_t>(c.integer("index"));
    f.stamp_s = c.number("stamp_s");
    f.status = c.text("status");
    f.point_times = c.text("point_times");
    f.deskewed = c.flag("deskewed");
    f.keyframe = c.flag("keyframe");
    f.x_m = c.number("x_m"), f.y_m = c.number("y_m"), f.z_m = c.number("z_m");
    f.points_in = static_cast<int>(c.integer("points_in"));
    f.points_registered = static_cast<int>(c.integer("points_registered"));
    f.iterations = static_cast<int>(c.integer("iterations"));
    f.inliers = static_cast<int>(c.integer("inliers"));
    f.fitness_m = c.real("fitness_m"), f.threshold_m = c.real("threshold_m");
    f.weak_directions = static_cast<int>(c.integer("weak_directions"));
    f.motion_information = c.real("motion_information");  // nan: not computed
    f.ms_preprocess = c.number("ms_preprocess"), f.ms_register = c.number("ms_register");
    f.ms_map = c.number("ms_map"), f.ms_total = c.number("ms_total");
    f.reason = c.text("reason");
    rows.push_back(std::move(f));
  }
  return rows;
}

}  // namespace roadslam::runfolder
