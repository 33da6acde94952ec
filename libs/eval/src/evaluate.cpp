#include "roadslam/eval/evaluate.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "roadslam/eval/plot.h"

namespace roadslam::eval {
namespace {

int columnsOfFirstDataLine(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot open trajectory '" + path + "'");
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    int n = 0;
    double v;
    while (ss >> v) ++n;
    return n;
  }
  throw std::runtime_error("trajectory '" + path + "' holds no pose");
}

/// The first displacement of at least \p min_m from the first pose, in the first pose's frame; zero
/// when the trajectory never moves that far.
Eigen::Vector3d firstMotion(const datasets::PoseList& poses, double min_m) {
  if (poses.empty()) return Eigen::Vector3d::Zero();
  for (const auto& T : poses) {
    const Eigen::Vector3d d = poses.front().rotation().transpose() * (T.translation() - poses.front().translation());
    if (d.norm() >= min_m) return d;
  }
  return Eigen::Vector3d::Zero();
}

/// KITTI odometry's ground truth holds camera 0's poses (x right, y down, z forward): a car moves along
/// its z axis. A LiDAR trajectory (x forward, z up) moves in its x-y plane. Told apart by the first
/// 2 m of motion of each, in its own first pose's frame.
void refuseCameraFrameGt(const MatchedTrajectories& m, const EvalRequest& req) {
  const Eigen::Vector3d g = firstMotion(m.gt, 2.0), e = firstMotion(m.est, 2.0);
  if (g.isZero() || e.isZero()) return;
  if (std::abs(g.z()) > 0.8 * g.norm() && std::abs(e.z()) < 0.3 * e.norm()) {
    throw std::runtime_error("'" + req.gt_path + "' moves along its z axis, as KITTI odometry's camera-frame poses "
                             "(z forward) do, and '" + req.est_path + "' in its x-y plane: give the sequence's "
                             "calib.txt with --calib to turn the ground truth into LiDAR poses");
  }
}

}  // namespace

datasets::Trajectory readTrajectoryAnyFormat(const std::string& path, const std::string& times_path) {
  const int cols = columnsOfFirstDataLine(path);
  if (cols == 8) return datasets::readTum(path);
  if (cols == 12) {
    if (!times_path.empty()) return datasets::readKittiTrajectory(path, times_path);
    datasets::Trajectory t;
    t.poses = datasets::readKittiPoses(path);
    return t;
  }
  throw std::runtime_error("'" + path + "': " + std::to_string(cols) +
                           " columns, expected 8 (TUM: t x y z qx qy qz qw) or 12 (KITTI 3x4)");
}

EvalOutcome evaluate(const EvalRequest& req) {
  auto gt = readTrajectoryAnyFormat(req.gt_path, req.gt_times_path);
  if (!req.gt_calib_path.empty()) {
    gt.poses = datasets::cameraPosesToVelodyne(gt.poses, datasets::readKittiOdometryCalib(req.gt_calib_path).T_cam0_velo);
  }
  const auto est = readTrajectoryAnyFormat(req.est_path, req.est_times_path);
  // Pairing a timed file with an untimed one by index pairs unrelated poses: refused.
  if (gt.stamps_s.empty() != est.stamps_s.empty()) {
    const bool gt_untimed = gt.stamps_s.empty();
    throw std::runtime_error("'" + (gt_untimed ? req.gt_path : req.est_path) +
                             "' is a KITTI 3x4 file without times and '" + (gt_untimed ? req.est_path : req.gt_path) +
                             "' has them: give " + (gt_untimed ? "--gt-times" : "--est-times") +
                             " (the drive's times.txt), or two files without times to pair by index");
  }
  EvalOutcome out;
  out.matched = associate(gt, est, req.max_dt_s);
  out.est_poses = est.poses.size();
  out.gt_poses = gt.poses.size();
  out.paired_by_time = !gt.stamps_s.empty() && !est.stamps_s.empty();
  if (const size_t paired = out.matched.gt.size(); paired < req.min_paired_fraction * static_cast<double>(out.est_poses)) {
    char buf[512];
    std::snprintf(buf, sizeof buf, "only %zu of the estimate's %zu poses (%.0f %%) paired with one of the %zu ground-truth poses",
                  paired, out.est_poses, 100.0 * static_cast<double>(paired) / static_cast<double>(std::max<size_t>(out.est_poses, 1)),
                  out.gt_poses);
    std::string w = buf;
    if (out.paired_by_time) {
      std::snprintf(buf, sizeof buf, " within max dt %g s: check both files' clocks and units, or --max-dt", req.max_dt_s);
      w += buf;
    } else {
      w += " (paired by index: a file without stamps)";
    }
    out.warnings.push_back(w);
  }
  if (out.matched.gt.size() < 2) {
    throw std::runtime_error("only " + std::to_string(out.matched.gt.size()) + " poses of '" +
                             req.est_path + "' match '" + req.gt_path +
                             "' in time (tolerance " + std::to_string(req.max_dt_s) + " s)");
  }
  if (req.gt_calib_path.empty()) refuseCameraFrameGt(out.matched, req);
  try {
    out.metrics = computeMetrics(out.matched, req.metrics);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  if (out.metrics.path_length_m < 0.01) {  // relative errors per distance would divide by nothing
    char buf[160];
    std::snprintf(buf, sizeof buf, "the %d matched ground-truth poses span %.3f m: no motion to score", out.metrics.matched_poses,
                  out.metrics.path_length_m);
    throw std::runtime_error(buf);
  }
  if (!req.plot_path.empty()) {
    plotTrajectories(req.plot_path, out.matched, out.metrics, req.est_path + " vs " + req.gt_path);
  }
  return out;
}

nlohmann::json toJson(const TrajectoryMetrics& m) {
  nlohmann::json j;
  j["matched_poses"] = m.matched_poses;
  j["path_length_m"] = m.path_length_m;
  j["ate_rmse_m"] = m.ate_rmse_m;
  j["ate_rmse_origin_aligned_m"] = m.ate_rmse_origin_aligned_m;
  j["ate_max_m"] = m.ate_max_m;
  j["rpe_trans_rmse_m"] = m.rpe_trans_rmse_m;
  j["rpe_rot_rmse_deg"] = m.rpe_rot_rmse_deg;
  j["rte_percent"] = m.rte_percent;
  j["rre_deg_per_100m"] = m.rre_deg_per_100m;
  j["final_position_error_m"] = m.final_position_error_m;
  auto& seg = j["segments"] = nlohmann::json::array();
  for (const auto& s : m.per_length) {
    seg.push_back({{"length_m", s.length_m},
                   {"rte_percent", s.t_err_percent},
                   {"rre_deg_per_100m", s.r_err_deg_per_100m},
                   {"count", s.segments}});
  }
  return j;
}

nlohmann::json toJson(const EvalOutcome& o, const EvalRequest& req) {
  nlohmann::json j = toJson(o.metrics);
  j["est_poses"] = o.est_poses;
  j["gt_poses"] = o.gt_poses;
  j["paired_by"] = o.paired_by_time ? "time" : "index";
  j["max_dt_s"] = req.max_dt_s;
  j["gt_calib"] = req.gt_calib_path;
  j["warnings"] = o.warnings;
  return j;
}

std::string toText(const TrajectoryMetrics& m) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "matched poses      %d over %.1f m\n"
                "ATE RMSE           %.3f m (SE(3)-aligned), %.3f m (first pose aligned), max %.3f m\n"
                "RPE (frame-frame)  %.4f m, %.4f deg\n"
                "KITTI rel. error   %.3f %% translation, %.4f deg/100 m rotation\n"
                "final pos. error   %.3f m (first pose aligned)\n",
                m.matched_poses, m.path_length_m, m.ate_rmse_m, m.ate_rmse_origin_aligned_m,
                m.ate_max_m, m.rpe_trans_rmse_m, m.rpe_rot_rmse_deg, m.rte_percent,
                m.rre_deg_per_100m, m.final_position_error_m);
  return buf;
}

}  // namespace roadslam::eval
