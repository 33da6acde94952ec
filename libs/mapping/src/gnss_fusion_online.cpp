#include "roadslam/mapping/gnss_fusion_online.h"

#include <algorithm>

namespace roadslam::mapping {

void OnlineGnssFusion::addFix(const GnssFactor& f) { fixes_.push_back(f); }

std::optional<Eigen::Isometry3d> OnlineGnssFusion::addNode(double t_s, const Eigen::Isometry3d& T_map_node) {
  t_.push_back(t_s);
  T_.push_back(T_map_node);
  while (t_.size() > 1 && t_.front() < t_s - p_.online_window_s) {
    t_.pop_front();
    T_.pop_front();
  }
  while (!fixes_.empty() && fixes_.front().t_s < t_.front() - p_.max_time_offset_s) fixes_.pop_front();
  if (t_s - last_solve_s_ >= p_.online_solve_period_s) solve();
  if (!anchored_) return std::nullopt;
  return published(t_s) * T_map_node;
}

Eigen::Isometry3d OnlineGnssFusion::published(double t_s) const {
  const double a = p_.online_blend_s > 0 ? std::clamp((t_s - blend_start_s_) / p_.online_blend_s, 0.0, 1.0) : 1.0;
  if (a >= 1.0) return C_to_;
  Eigen::Isometry3d C = Eigen::Isometry3d::Identity();
  C.linear() = Eigen::Quaterniond(C_from_.rotation()).slerp(a, Eigen::Quaterniond(C_to_.rotation())).toRotationMatrix();
  C.translation() = (1 - a) * C_from_.translation() + a * C_to_.translation();
  return C;
}

void OnlineGnssFusion::solve() {
  last_solve_s_ = t_.back();
  if (!anchored_ && p_.online_min_path_m > 0) {
    double path = 0;
    for (std::size_t i = 1; i < T_.size(); ++i) path += (T_[i].translation() - T_[i - 1].translation()).norm();
    if (path < p_.online_min_path_m) return;  // not a solve yet: too little path to anchor on
  }
  const std::vector<double> stamps(t_.begin(), t_.end());
  const PoseVector poses(T_.begin(), T_.end());
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
  const Eigen::Isometry3d C_new = r.T_enu_node.back() * poses.back().inverse();
  C_from_ = anchored_ ? published(last_solve_s_) : C_new;  // the first correction applies at once
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

}  // namespace roadslam::mapping
