#include "roadslam/eval/trajectory_metrics.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace roadslam::eval {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

double rotationAngle(const Eigen::Matrix3d& R) {
  // 2 atan2(|v|, |w|) of the unit quaternion: unlike the devkit's acos((tr R - 1) / 2) it keeps its
  // precision near zero, where 3x4 files printed with 6-9 digits leave R slightly non-orthonormal.
  const Eigen::Quaterniond q(R);
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

std::vector<double> cumulativeDistance(const datasets::PoseList& poses) {
  std::vector<double> d(poses.size(), 0.0);
  for (size_t i = 1; i < poses.size(); ++i) {
    d[i] = d[i - 1] + (poses[i].translation() - poses[i - 1].translation()).norm();
  }
  return d;
}

std::vector<double> defaultLengths(double path_m) {
  if (path_m >= 800.0) return {100, 200, 300, 400, 500, 600, 700, 800};
  std::vector<double> out;
  for (int k = 1; k <= 9; ++k) out.push_back(path_m * k / 10.0);
  return out;
}

void kittiSegments(const MatchedTrajectories& m, const std::vector<double>& dist,
                   const MetricsParams& p, TrajectoryMetrics& out) {
  const auto lengths = p.segment_lengths_m.empty() ? defaultLengths(dist.back()) : p.segment_lengths_m;
  double t_sum = 0, r_sum = 0;
  int n_all = 0;
  const int step = std::max(1, p.segment_step_frames);
  for (double len : lengths) {
    KittiSegmentError se;
    se.length_m = len;
    if (len <= 0) continue;
    for (size_t first = 0; first < dist.size(); first += step) {
      // last frame whose travelled distance from `first` reaches len (devkit lastFrameFromSegmentLength)
      const auto it = std::lower_bound(dist.begin() + first, dist.end(), dist[first] + len);
      if (it == dist.end()) break;
      const size_t last = static_cast<size_t>(it - dist.begin());
      const Eigen::Isometry3d d_gt = m.gt[first].inverse() * m.gt[last];
      const Eigen::Isometry3d d_est = m.est[first].inverse() * m.est[last];
      const Eigen::Isometry3d e = d_est.inverse() * d_gt;
      se.t_err_percent += 100.0 * e.translation().norm() / len;
      se.r_err_deg_per_100m += 100.0 * rotationAngle(e.rotation()) * kRadToDeg / len;
      ++se.segments;
    }
    if (se.segments == 0) continue;
    t_sum += se.t_err_percent;
    r_sum += se.r_err_deg_per_100m;
    n_all += se.segments;
    se.t_err_percent /= se.segments;
    se.r_err_deg_per_100m /= se.segments;
    out.per_length.push_back(se);
  }
  if (n_all > 0) {
    out.rte_percent = t_sum / n_all;
    out.rre_deg_per_100m = r_sum / n_all;
  }
}

}  // namespace

MatchedTrajectories associate(const datasets::Trajectory& gt, const datasets::Trajectory& est,
                              double max_dt_s) {
  MatchedTrajectories m;
  const bool timed = gt.stamps_s.size() == gt.poses.size() && est.stamps_s.size() == est.poses.size() &&
                     !gt.stamps_s.empty() && !est.stamps_s.empty();
  if (!timed) {
    const size_t n = std::min(gt.poses.size(), est.poses.size());
    for (size_t i = 0; i < n; ++i) {
      m.gt.push_back(gt.poses[i]);
      m.est.push_back(est.poses[i]);
      m.stamps_s.push_back(static_cast<double>(i));
    }
    return m;
  }
  for (size_t i = 0; i < est.poses.size(); ++i) {
    const double t = est.stamps_s[i];
    const auto it = std::lower_bound(gt.stamps_s.begin(), gt.stamps_s.end(), t);
    size_t best = gt.stamps_s.size();
    double best_dt = max_dt_s;
    for (auto c : {it, it == gt.stamps_s.begin() ? it : it - 1}) {
      if (c == gt.stamps_s.end()) continue;
      const double dt = std::abs(*c - t);
      if (dt <= best_dt) {
        best_dt = dt;
        best = static_cast<size_t>(c - gt.stamps_s.begin());
      }
    }
    if (best == gt.stamps_s.size()) continue;
    m.gt.push_back(gt.poses[best]);
    m.est.push_back(est.poses[i]);
    m.stamps_s.push_back(t);
  }
  return m;
}

Eigen::Isometry3d alignUmeyama(const datasets::PoseList& gt, const datasets::PoseList& est) {
  if (gt.size() != est.size() || gt.size() < 3) {
    throw std::invalid_argument("alignment needs at least 3 matched poses");
  }
  Eigen::Matrix3Xd src(3, est.size()), dst(3, gt.size());
  for (size_t i = 0; i < gt.size(); ++i) {
    src.col(i) = est[i].translation();
    dst.col(i) = gt[i].translation();
  }
  Eigen::Isometry3d T;
  T.matrix() = Eigen::umeyama(src, dst, false);
  return T;
}

TrajectoryMetrics computeMetrics(const MatchedTrajectories& m, const MetricsParams& p) {
  if (m.gt.size() != m.est.size() || m.gt.size() < 2) {
    throw std::invalid_argument("metrics need at least 2 matched poses, got " +
                                std::to_string(m.gt.size()));
  }
  TrajectoryMetrics out;
  const size_t n = m.gt.size();
  out.matched_poses = static_cast<int>(n);
  out.distance_m = cumulativeDistance(m.gt);
  out.path_length_m = out.distance_m.back();
  out.T_gt_est = n >= 3 ? alignUmeyama(m.gt, m.est) : m.gt[0] * m.est[0].inverse();
  const Eigen::Isometry3d T_origin = m.gt[0] * m.est[0].inverse();

  double se = 0, se_origin = 0, rpe_t = 0, rpe_r = 0;
  for (size_t i = 0; i < n; ++i) {
    const double e = (m.gt[i].translation() - out.T_gt_est * m.est[i].translation()).norm();
    const double eo = (m.gt[i].translation() - T_origin * m.est[i].translation()).norm();
    out.ate_error_m.push_back(e);
    out.ate_max_m = std::max(out.ate_max_m, e);
    se += e * e;
    se_origin += eo * eo;
    if (i + 1 < n) {
      const Eigen::Isometry3d d = (m.est[i].inverse() * m.est[i + 1]).inverse() *
                                  (m.gt[i].inverse() * m.gt[i + 1]);
      rpe_t += d.translation().squaredNorm();
      const double a = rotationAngle(d.rotation()) * kRadToDeg;
      rpe_r += a * a;
    }
  }
  out.ate_rmse_m = std::sqrt(se / n);
  out.ate_rmse_origin_aligned_m = std::sqrt(se_origin / n);
  out.rpe_trans_rmse_m = std::sqrt(rpe_t / (n - 1));
  out.rpe_rot_rmse_deg = std::sqrt(rpe_r / (n - 1));
  out.final_position_error_m =
      (m.gt.back().translation() - T_origin * m.est.back().translation()).norm();
  kittiSegments(m, out.distance_m, p, out);
  return out;
}

}  // namespace roadslam::eval
