#include "roadslam/boundary/job.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <map>
#include <sstream>

#include "roadslam/boundary/detector.h"
#include "roadslam/boundary/output.h"
#include "roadslam/boundary/poses.h"
#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/progress.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/pipeline/scan_stream.h"

namespace fs = std::filesystem;

namespace roadslam::boundary {
namespace {

double sweepDuration(const Scan& s) {
  double d = 0;
  for (const auto& q : s.points) d = std::max<double>(d, q.t);
  return d;
}

/// Pose source: a given trajectory, or the odometry (constant velocity within a sweep).
class PoseSource {
 public:
  PoseSource(const std::string& tum, const mrpt::config::CConfigFileBase& cfg) {
    if (!tum.empty()) {
      traj_ = datasets::readTum(tum);
      return;
    }
    odometry::Params op;
    op.loadFromConfigFile(cfg);
    odo_ = std::make_unique<odometry::Odometry>(op);
  }
  /// Deskews \p scan into the lidar frame at T_map_ref; false (and \p why) without a pose.
  bool apply(Scan& scan, Eigen::Isometry3d& T_map_ref, double& t_ref, std::string& why) {
    const double dur = sweepDuration(scan);
    t_ref = scan.stamp_s + 0.5 * dur;
    if (!odo_) {
      const auto a = interpolatePose(traj_.stamps_s, traj_.poses, scan.stamp_s);
      const auto b = interpolatePose(traj_.stamps_s, traj_.poses, scan.stamp_s + dur);
      const auto r = interpolatePose(traj_.stamps_s, traj_.poses, t_ref);
      if (!a || !b || !r) {
        why = "no pose in the trajectory at this sweep";
        return false;
      }
      T_map_ref = *r;
      deskewBetween(scan, *a, *b, dur, T_map_ref);
      return true;
    }
    const auto res = odo_->process(scan);
    if (res.status == odometry::FrameStatus::Skipped) {
      why = "odometry skipped the sweep";
      return false;
    }
    T_map_ref = res.T_world_lidar;
    t_ref = res.stamp_s;
    const Eigen::Isometry3d half = interpolate(Eigen::Isometry3d::Identity(), T_prev_.inverse() * T_map_ref, 0.5);
    if (have_prev_ && dur > 0) deskewBetween(scan, T_map_ref * half.inverse(), T_map_ref * half, dur, T_map_ref);
    T_prev_ = T_map_ref, have_prev_ = true;
    return true;
  }

 private:
  datasets::Trajectory traj_;
  std::unique_ptr<odometry::Odometry> odo_;
  Eigen::Isometry3d T_prev_ = Eigen::Isometry3d::Identity();
  bool have_prev_ = false;
};

struct Totals {
  size_t frames = 0, no_pose = 0, left = 0, right = 0, both = 0;
  double ms_sum = 0, ms_max = 0;
  std::map<std::string, size_t> status, reasons;
  void add(const BoundaryFrame& f) {
    ++frames, ++status[f.status];
    ms_sum += f.ms, ms_max = std::max(ms_max, f.ms);
    left += f.left.found, right += f.right.found, both += f.left.found && f.right.found;
    if (!f.left.found) ++reasons["left: " + f.left.reason.substr(0, f.left.reason.find(" ("))];
    if (!f.right.found) ++reasons["right: " + f.right.reason.substr(0, f.right.reason.find(" ("))];
  }
};

}  // namespace

nlohmann::json runBoundsJob(const BoundsRequest& req) {
  const auto cfg = loadIniFile(req.config_path);
  Params params;
  params.loadFromConfigFile(*cfg);
  std::error_code ec;
  fs::create_directories(req.out_dir + "/frames", ec);
  if (ec) throw std::runtime_error("cannot create output folder '" + req.out_dir + "': " + ec.message());
  mrpt::config::CConfigFileMemory used;
  params.saveToConfigFile(used);
  writeFileAtomically(req.out_dir + "/config_used.ini", used.getContent());
  auto stream = pipeline::openScanStream(req.input_path, *cfg);
  PoseSource poses(req.trajectory_path, *cfg);
  BoundaryDetector det(params);
  AtomicFile jsonl(req.out_dir + "/boundaries.jsonl");
  Totals tot;
  ProgressBar bar("roadslam-bounds", stream->sizeHint());
  std::string last_png;
  while (auto scan = stream->next()) {
    if (stopRequested() || (req.max_frames && tot.frames + tot.no_pose >= req.max_frames)) break;
    Eigen::Isometry3d T;
    double t_ref = 0;
    std::string why;
    if (!poses.apply(*scan, T, t_ref, why)) {
      ++tot.no_pose;
      jsonl.stream() << nlohmann::json{{"stamp_s", scan->stamp_s}, {"status", "no_pose"}, {"reason", why}}.dump() << "\n";
      continue;
    }
    const BoundaryFrame f = det.process(*scan, T, t_ref);
    tot.add(f);
    jsonl.stream() << toJson(f).dump() << "\n";
    if (req.png_every > 0 && f.index % static_cast<size_t>(req.png_every) == 0) {
      char name[32];
      std::snprintf(name, sizeof name, "frames/%06zu.png", f.index);
      last_png = req.out_dir + "/" + name;
      drawTopView(last_png, *scan, det.lastLabelling(), f, 8.0, det.curbMap().inVehicle(T));
      std::snprintf(name, sizeof name, "frames/%06zu_cost.png", f.index);
      writeCostGridPng(req.out_dir + "/" + name, f.grid);
    }
    if (req.progress) bar.update(tot.frames);
  }
  jsonl.commit();
  if (!last_png.empty()) fs::copy_file(last_png, req.out_dir + "/top_view.png", fs::copy_options::overwrite_existing);
  const double n = static_cast<double>(std::max<size_t>(tot.frames, 1));
  nlohmann::json s = {{"input", stream->describe()}, {"method", params.method}, {"frames", tot.frames},
                      {"frames_without_pose", tot.no_pose}, {"ms_per_frame_mean", tot.ms_sum / n},
                      {"ms_per_frame_max", tot.ms_max}, {"left_found_rate", tot.left / n},
                      {"right_found_rate", tot.right / n}, {"both_found_rate", tot.both / n},
                      {"status", tot.status}, {"not_found_reasons", tot.reasons},
                      {"poses", req.trajectory_path.empty() ? "odometry" : req.trajectory_path}};
  writeFileAtomically(req.out_dir + "/summary.json", s.dump(2) + "\n");
  return s;
}

}  // namespace roadslam::boundary
