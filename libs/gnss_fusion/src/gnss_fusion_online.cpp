#include "roadslam/gnss_fusion/gnss_fusion_online.h"

#include <algorithm>
#include <cmath>

namespace roadslam::gnss_fusion {

void OnlineGnssFusion::addFix(const GnssFactor& f) { fixes_.push_back(f); }

std::optional<Eigen::Isometry3d> OnlineGnssFusion::addNode(double t_s, const Eigen::Isometry3d& T_map_node) {
  D_.push_back(T_.empty() ? T_map_node : step(D_.back(), T_.back().inverse() * T_map_node, t_s - t_.back()));
  t_.push_back(t_s);
  T_.push_back(T_map_node);
  while (t_.size() > 1 && t_.front() < t_s - p_.online_window_s) {
    t_.pop_front();
    T_.pop_front();
    D_.pop_front();
  }
  while (!fixes_.empty() && fixes_.front().t_s < t_.front() - p_.max_time_offset_s) fixes_.pop_front();
  if (t_s - last_solve_s_ >= p_.online_solve_period_s) solve();
  if (!anchored_) return std::nullopt;
  return published(t_s, D_.back());
}

Eigen::Isometry3d OnlineGnssFusion::step(const Eigen::Isometry3d& T_prev, const Eigen::Isometry3d& d, double dt_s) const {
  Eigen::Isometry3d d_scaled = d;
  d_scaled.translation() *= scale_;
  Eigen::Isometry3d T = T_prev * d_scaled;
  if (c_radps_ != 0) T.linear() = Eigen::AngleAxisd(c_radps_ * dt_s, Eigen::Vector3d::UnitZ()).toRotationMatrix() * T.linear();
  return T;
}

namespace {
double yawOf(const Eigen::Matrix3d& R) { return std::atan2(R(1, 0), R(0, 0)); }
}  // namespace

void OnlineGnssFusion::updateBias(const PoseVector& window, const PoseVector& fused) {
  double path = 0;
  for (std::size_t i = 1; i < window.size(); ++i) path += (window[i].translation() - window[i - 1].translation()).norm();
  if (path < p_.online_bias_min_path_m) return;
  // heading of the fused minus the input, unwrapped; the line through it in time, weighted by the
  // path each node stands for (a stopped car's heading says nothing about the rate)
  double sw = 0, st = 0, sy = 0, stt = 0, sty = 0, prev = 0, unwrapped = 0;
  for (std::size_t i = 0; i < window.size(); ++i) {
    const double d = yawOf(fused[i].linear() * window[i].linear().transpose());
    unwrapped = i == 0 ? d : unwrapped + std::remainder(d - prev, 2 * M_PI);
    prev = d;
    const double w = i == 0 ? 0 : (window[i].translation() - window[i - 1].translation()).norm();
    const double t = t_[i] - t_.front();
    sw += w, st += w * t, sy += w * unwrapped, stt += w * t * t, sty += w * t * unwrapped;
  }
  const double den = sw * stt - st * st;
  if (p_.online_yaw_rate_bias && den > 0) {
    c_radps_ += (sw * sty - st * sy) / den;
    stats_.yaw_rate_correction_radps = c_radps_;
  }
  if (p_.online_odometry_scale) {
    // the fused steps against the input steps turned into ENU by the fused heading: the least-squares
    // ratio sum(f.u) / sum(u.u), linear in f so the fixes' noise does not lengthen it
    double fu = 0, uu = 0;
    for (std::size_t i = 1; i < window.size(); ++i) {
      const Eigen::Vector3d u = fused[i - 1].linear() * (window[i - 1].inverse() * window[i]).translation();
      fu += (fused[i].translation() - fused[i - 1].translation()).dot(u);
      uu += u.squaredNorm();
    }
    if (uu > 0) scale_ *= fu / uu;
    stats_.scale = scale_;
  }
  ++stats_.bias_updates;
}

Eigen::Isometry3d OnlineGnssFusion::published(double t_s, const Eigen::Isometry3d& T_map_node) const {
  const double a = p_.online_blend_s > 0 ? std::clamp((t_s - blend_start_s_) / p_.online_blend_s, 0.0, 1.0) : 1.0;
  if (a >= 1.0) return C_to_ * T_map_node;
  // the two poses blended, not the two corrections: a rotation blended about the map's origin swings
  // a node far from it along an arc (|p| theta^2 / 8 off the chord at half way)
  const Eigen::Isometry3d A = C_from_ * T_map_node, B = C_to_ * T_map_node;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(A.rotation()).slerp(a, Eigen::Quaterniond(B.rotation())).toRotationMatrix();
  T.translation() = (1 - a) * A.translation() + a * B.translation();
  return T;
}

void OnlineGnssFusion::solve() {
  last_solve_s_ = t_.back();
  if (!anchored_ && p_.online_min_path_m > 0) {
    double path = 0;
    for (std::size_t i = 1; i < T_.size(); ++i) path += (T_[i].translation() - T_[i - 1].translation()).norm();
    if (path < p_.online_min_path_m) return;  // not a solve yet: too little path to anchor on
  }
  const std::vector<double> stamps(t_.begin(), t_.end());
  PoseVector poses{D_.front()};  // the window re-integrated with the current c
  for (std::size_t i = 1; i < T_.size(); ++i) poses.push_back(step(poses.back(), T_[i - 1].inverse() * T_[i], t_[i] - t_[i - 1]));
  const std::vector<GnssFactor> fixes(fixes_.begin(), fixes_.end());
  const GnssFusionResult r = fuseGnss(stamps, poses, fixes, p_);
  ++stats_.solves;
  stats_.ms_total += r.ms;
  stats_.ms_max = std::max(stats_.ms_max, r.ms);
  if (!r.ok) {  // keep the last correction: the odometry carries the pose on
    ++stats_.failed;
    return;
  }
  stats_.rejected += r.rejected;
  if (p_.online_yaw_rate_bias || p_.online_odometry_scale) updateBias(poses, r.T_enu_node);
  // the frames to come extend the stream as integrated so far (D_), so the correction maps its newest pose
  const Eigen::Isometry3d C_new = r.T_enu_node.back() * D_.back().inverse();
  C_from_ = anchored_ ? published(last_solve_s_, D_.back()) * D_.back().inverse() : C_new;  // the first correction applies at once
  C_to_ = C_new;
  blend_start_s_ = last_solve_s_;
  anchored_ = true;
}

std::vector<std::optional<Eigen::Isometry3d>> replayOnline(const std::vector<double>& stamps_s,
                                                           const PoseVector& T_map_node,
                                                           const std::vector<GnssFactor>& fixes,
                                                           const GnssFusionParams& p, GnssOnlineStats* stats) {
  std::vector<const GnssFactor*> order;
  for (const auto& f : fixes) order.push_back(&f);
  std::stable_sort(order.begin(), order.end(), [](const GnssFactor* a, const GnssFactor* b) { return a->t_s < b->t_s; });
  OnlineGnssFusion online(p);
  std::vector<std::optional<Eigen::Isometry3d>> out;
  std::size_t k = 0;
  for (std::size_t i = 0; i < stamps_s.size(); ++i) {
    while (k < order.size() && order[k]->t_s <= stamps_s[i]) online.addFix(*order[k++]);
    out.push_back(online.addNode(stamps_s[i], T_map_node[i]));
  }
  if (stats) *stats = online.stats();
  return out;
}

}  // namespace roadslam::gnss_fusion
