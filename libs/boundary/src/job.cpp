#include "roadslam/boundary/job.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <chrono>
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
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/sources/scan_source.h"
#include "roadslam/velodyne/decoder_params.h"

namespace fs = std::filesystem;

namespace roadslam::boundary {
namespace {

double sweepDuration(const Scan& s) {
  double d = 0;
  for (const auto& q : s.points) d = std::max<double>(d, q.t);
  return d;
}

/// A sweep's pose: the lidar at the sweep's start and end (the deskew's ends) and at its reference
/// time t_ref (the frame the sweep is deskewed into, T_map_lidar), or why there is none.
struct SweepPose {
  double stamp_s = 0;  ///< the sweep's stamp (its first point) [s]
  bool ok = false;
  std::string why;
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity(), end = Eigen::Isometry3d::Identity(),
                    ref = Eigen::Isometry3d::Identity();
  double t_ref = 0, dur = 0;  ///< [s]
  bool deskew = false;
};

void deskew(Scan& scan, const SweepPose& sp) {
  if (sp.deskew) deskewBetween(scan, sp.start, sp.end, sp.dur, sp.ref);
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
  SweepPose pose(const Scan& scan) {
    SweepPose sp;
    sp.stamp_s = scan.stamp_s;
    sp.dur = sweepDuration(scan);
    sp.t_ref = scan.stamp_s + 0.5 * sp.dur;
    if (!odo_) {
      const auto a = interpolatePose(traj_.stamps_s, traj_.poses, scan.stamp_s);
      const auto b = interpolatePose(traj_.stamps_s, traj_.poses, scan.stamp_s + sp.dur);
      const auto r = interpolatePose(traj_.stamps_s, traj_.poses, sp.t_ref);
      if (!a || !b || !r) {
        sp.why = "no pose in the trajectory at this sweep";
        return sp;
      }
      sp.ok = sp.deskew = true, sp.start = *a, sp.end = *b, sp.ref = *r;
      return sp;
    }
    const auto res = odo_->process(scan);
    if (res.status == odometry::FrameStatus::Skipped) {
      sp.why = "odometry skipped the sweep";
      return sp;
    }
    sp.ok = true, sp.ref = res.T_world_lidar, sp.t_ref = res.stamp_s;
    const Eigen::Isometry3d half = interpolate(Eigen::Isometry3d::Identity(), T_prev_.inverse() * sp.ref, 0.5);
    sp.deskew = have_prev_ && sp.dur > 0;
    sp.start = sp.ref * half.inverse(), sp.end = sp.ref * half;
    T_prev_ = sp.ref, have_prev_ = true;
    return sp;
  }

 private:
  datasets::Trajectory traj_;
  std::unique_ptr<odometry::Odometry> odo_;
  Eigen::Isometry3d T_prev_ = Eigen::Isometry3d::Identity();
  bool have_prev_ = false;
};

bool enough(const BoundsRequest& req, size_t sweeps) { return stopRequested() || (req.max_frames && sweeps >= req.max_frames); }

struct Drive {
  std::vector<SweepPose> poses;  ///< one per sweep, in order
  double ms_mean = 0;            ///< detector time per sweep (labelling, curb map) [ms]
};

/// Whole-drive mode, first pass: every sweep's pose (the odometry runs here only) and its curb
/// points into \p det's curb map.
Drive accumulateDrive(const BoundsRequest& req, const mrpt::config::CConfigFileBase& cfg, BoundaryDetector& det) {
  Drive d;
  std::vector<SweepPose>& out = d.poses;
  auto stream = sources::openScanSource(req.input_path, cfg, req.times_path);
  PoseSource poses(req.trajectory_path, cfg);
  ProgressBar bar("roadslam-bounds: whole drive, pass 1", stream->sizeHint());
  size_t n = 0;
  while (auto scan = stream->next()) {
    if (enough(req, out.size())) break;
    out.push_back(poses.pose(*scan));
    if (out.back().ok) {
      deskew(*scan, out.back());
      const auto t0 = std::chrono::steady_clock::now();
      det.accumulate(*scan, out.back().ref, out.back().t_ref);
      d.ms_mean += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(), ++n;
    }
    if (req.progress) bar.update(out.size());
  }
  det.finishAccumulation();
  d.ms_mean /= static_cast<double>(std::max<size_t>(n, 1));
  return d;
}

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
  {
    // what the sweeps' source and the odometry read, in every mode, so their keys are checked too
    odometry::Params op;
    op.loadFromConfigFile(*cfg);
    velodyne::DecoderParams dp;
    dp.loadFromConfigFile(*cfg, "velodyne");
    datasets::KittiParams kp;
    kp.loadFromConfigFile(*cfg, "kitti");
  }
  const auto unknown_keys = cfg->checkEntries(req.allow_unknown_keys);
  {
    // an input that gives no sweep at all is an error before any output exists
    auto probe = sources::openScanSource(req.input_path, *cfg, req.times_path);
    if (!probe->next()) {
      const std::string err = probe->errorMessage();
      throw std::runtime_error("input '" + req.input_path + "' gives no sweep" + (err.empty() ? "" : ": " + err));
    }
  }
  // a trajectory that cannot be read fails here too (whole-drive mode reads it again in pass 1)
  std::unique_ptr<PoseSource> poses = std::make_unique<PoseSource>(req.trajectory_path, *cfg);
  if (req.whole_drive) poses.reset();
  std::error_code ec;
  fs::create_directories(req.out_dir + "/frames", ec);
  if (ec) throw std::runtime_error("cannot create output folder '" + req.out_dir + "': " + ec.message());
  mrpt::config::CConfigFileMemory used;
  params.saveToConfigFile(used);
  writeFileAtomically(req.out_dir + "/config_used.ini", used.getContent());
  BoundaryDetector det(params);
  Drive drive;  // whole-drive mode: pass 1's poses, replayed in pass 2
  if (req.whole_drive) drive = accumulateDrive(req, *cfg, det);
  const std::vector<SweepPose>& recorded = drive.poses;
  auto stream = sources::openScanSource(req.input_path, *cfg, req.times_path);
  AtomicFile jsonl(req.out_dir + "/boundaries.jsonl");
  Totals tot;
  ProgressBar bar("roadslam-bounds", stream->sizeHint());
  std::string last_png;
  while (auto scan = stream->next()) {
    const size_t i = tot.frames + tot.no_pose;
    if (enough(req, i) || (req.whole_drive && i >= recorded.size())) break;
    if (req.whole_drive && recorded[i].stamp_s != scan->stamp_s)
      throw std::runtime_error("'" + req.input_path + "' gave other sweeps on its second reading (sweep " + std::to_string(i) + ")");
    const SweepPose sp = req.whole_drive ? recorded[i] : poses->pose(*scan);
    if (!sp.ok) {
      ++tot.no_pose;
      jsonl.stream() << nlohmann::json{{"stamp_s", scan->stamp_s}, {"status", "no_pose"}, {"reason", sp.why}}.dump() << "\n";
      continue;
    }
    deskew(*scan, sp);
    const Eigen::Isometry3d& T = sp.ref;
    const BoundaryFrame f = det.process(*scan, T, sp.t_ref);
    tot.add(f);
    jsonl.stream() << toJson(f).dump() << "\n";
    if (req.png_every > 0 && f.index % static_cast<size_t>(req.png_every) == 0) {
      char name[32];
      std::snprintf(name, sizeof name, "frames/%06zu.png", f.index);
      last_png = req.out_dir + "/" + name;
      drawTopView(last_png, *scan, det.lastLabelling(), f, 8.0, det.fitCells(T));
      std::snprintf(name, sizeof name, "frames/%06zu_cost.png", f.index);
      writeCostGridPng(req.out_dir + "/" + name, f.grid);
    }
    if (req.progress) bar.update(tot.frames);
  }
  jsonl.commit();
  if (!last_png.empty()) fs::copy_file(last_png, req.out_dir + "/top_view.png", fs::copy_options::overwrite_existing);
  const double n = static_cast<double>(std::max<size_t>(tot.frames, 1));
  nlohmann::json s = {{"input", stream->describe()}, {"method", toString(params.method)}, {"frames", tot.frames},
                      {"frames_without_pose", tot.no_pose}, {"ms_per_frame_mean", tot.ms_sum / n},
                      {"ms_per_frame_max", tot.ms_max}, {"left_found_rate", tot.left / n},
                      {"right_found_rate", tot.right / n}, {"both_found_rate", tot.both / n},
                      {"status", tot.status}, {"not_found_reasons", tot.reasons},
                      {"poses", req.trajectory_path.empty() ? "odometry" : req.trajectory_path},
                      {"mode", req.whole_drive ? "whole_drive" : "live"}, {"curb_map_cells", det.curbMap().size()}};
  if (req.whole_drive) s["ms_per_frame_first_pass_mean"] = drive.ms_mean;
  s["warnings"] = unknown_keys;
  if (!stream->errorMessage().empty()) s["warnings"].push_back("input damaged: " + stream->errorMessage());
  s["complete"] = stream->errorMessage().empty() && !stopRequested();
  for (const auto& w : stream->warnings()) s["warnings"].push_back(w);
  writeFileAtomically(req.out_dir + "/summary.json", s.dump(2) + "\n");
  return s;
}

}  // namespace roadslam::boundary
