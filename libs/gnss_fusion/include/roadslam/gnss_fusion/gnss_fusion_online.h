#pragma once
/// \file gnss_fusion_online.h
/// The online GNSS mode: corrects the pose published while driving, using only what has
/// arrived so far (causal: no later fix, no later frame). A sliding-window smoother over fuseGnss():
/// the frames of the last GnssFusionParams::online_window_s and the fixes among them are re-solved
/// every online_solve_period_s; the newest frame's fused pose gives the correction
/// C = T_enu_node * T_map_node^-1, and every frame until the next solve is published as C T_map_node
/// (the odometry carries the pose forward between solves and through outages). A new correction is
/// blended in over online_blend_s from the one published at that moment, so a re-solve never makes
/// the published pose jump by its whole change at once.
///
/// With online_yaw_rate_bias, a yaw-rate correction c [rad/s] is a state carried from solve to solve:
/// the odometry is re-integrated with its increments turned by c dt about the map's z axis (the
/// increment's translation stays in the previous heading: R' = Rz(c dt) R ΔR, t' = t + R Δt), the
/// window is solved on that, and c grows by the slope of the fused-minus-input heading over the
/// window's time (weighted least squares line, heading unwrapped). Tight rotation factors let a solve
/// bend only part of a residual bias, so c converges over a few solves rather than at once; each
/// window is rebuilt with the current c so the slope measures only what is left.
///
/// With online_odometry_scale, a scale of the increments' translation is carried the same way: it is
/// multiplied by the least-squares ratio of the fused steps to the input steps (turned into ENU by
/// the fused heading) over the window.
///
/// The input must itself be causal: the odometry's own poses, not the loop-corrected ones (a loop
/// closure moves past poses after the fact).

#include <deque>
#include <optional>

#include "roadslam/gnss_fusion/gnss_fusion.h"

namespace roadslam::gnss_fusion {

struct GnssOnlineStats {
  std::size_t solves = 0;        ///< window solves run [count]
  std::size_t failed = 0;        ///< solves that could not run (too few fixes, too little motion) [count]
  std::size_t rejected = 0;      ///< fixes the newest solve counted rejected, summed over solves [count]
  double ms_total = 0, ms_max = 0;  ///< solve wall time [ms]
  double yaw_rate_correction_radps = 0;  ///< c, the newest estimate (minus the odometry's yaw-rate bias) [rad/s]
  double scale = 1;              ///< the odometry's translation scale estimate (online_odometry_scale) [-]
  std::size_t bias_updates = 0;  ///< solves that updated c or the scale [count]
};

class OnlineGnssFusion {
 public:
  explicit OnlineGnssFusion(const GnssFusionParams& p) : p_(p) {}
  /// A fix, as it arrives (its time t_s on the frames' clock, increasing).
  void addFix(const GnssFactor& f);
  /// The frame at \p t_s with its odometry pose; returns its corrected T_enu_node from the fixes added
  /// so far, or nothing before the first solve that could run.
  std::optional<Eigen::Isometry3d> addNode(double t_s, const Eigen::Isometry3d& T_map_node);
  bool anchored() const { return anchored_; }
  /// The correction T_enu_map of the newest solve (identity before the first).
  const Eigen::Isometry3d& correction() const { return C_to_; }
  const GnssOnlineStats& stats() const { return stats_; }

 private:
  void solve();
  /// Pose after \p T_prev by the odometry increment \p d over \p dt_s, turned by the yaw-rate correction.
  Eigen::Isometry3d step(const Eigen::Isometry3d& T_prev, const Eigen::Isometry3d& d, double dt_s) const;
  void updateBias(const PoseVector& window, const PoseVector& fused);
  /// The node's pose by the correction blended at t_s.
  Eigen::Isometry3d published(double t_s, const Eigen::Isometry3d& T_map_node) const;
  GnssFusionParams p_;
  std::deque<double> t_;
  std::deque<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> T_;  ///< as given
  std::deque<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> D_;  ///< re-integrated with c as it was
  double c_radps_ = 0;
  double scale_ = 1;  ///< multiplies the increments' translation
  std::deque<GnssFactor> fixes_;
  Eigen::Isometry3d C_from_ = Eigen::Isometry3d::Identity(), C_to_ = Eigen::Isometry3d::Identity();
  double blend_start_s_ = 0;
  bool anchored_ = false;
  double last_solve_s_ = -1e300;
  GnssOnlineStats stats_;
};

/// The online mode replayed over a finished run: frames and fixes merged in time order (a fix is
/// added once the frame clock reaches it). Returns one pose per frame; frames before the first
/// solve are std::nullopt.
std::vector<std::optional<Eigen::Isometry3d>> replayOnline(const std::vector<double>& stamps_s,
                                                           const PoseVector& T_map_node,
                                                           const std::vector<GnssFactor>& fixes,
                                                           const GnssFusionParams& p, GnssOnlineStats* stats = nullptr);

}  // namespace roadslam::gnss_fusion
