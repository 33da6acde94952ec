#pragma once
// Oracle for the simulated drives: how much of a ground-truth curb is in view at all, independent of
// the detector. A return counts as "on the curb face" when it lies within face_tol_m of the GT curb
// line and between the road and the curb top (flat drives: the road is sensor_height below the
// lidar). Per sweep: the fraction of the 1 m stations 5-30 m ahead (where the GT curb exists) holding
// such a return in this sweep, and in all sweeps so far (map frame, GT poses).
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "roadslam/boundary/poses.h"
#include "roadslam/common/config.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/eval/boundary_metrics.h"
#include "roadslam/pipeline/scan_stream.h"

namespace roadslam::boundary::test {

struct CurbView {
  double stamp_s = 0;            ///< reference time of the sweep [s]
  double sweep = 0, accum = 0;   ///< station coverage 5-30 m ahead, this sweep / all sweeps so far [-]
  int behind = 0, beyond = 0;    ///< stations -10..5 m / 30..45 m with face returns, all sweeps so far [-]
};

inline std::vector<CurbView> curbVisibility(const std::string& drive, const std::string& ini, int side,
                                            double sensor_height_m = 1.9, double curb_h_m = 0.15,
                                            double face_tol_m = 0.15) {
  const auto cfg = loadIniFile(ini);
  auto stream = pipeline::openScanStream(drive + "/velodyne.pcap", *cfg);
  const auto traj = datasets::readTum(drive + "/gt_trajectory.tum");
  const auto curbs = eval::readGtCurbs(drive + "/gt_boundaries.json");
  std::vector<Eigen::Vector2d> seen_map;  // face returns of all sweeps so far, map frame
  std::vector<CurbView> out;
  while (auto scan = stream->next()) {
    double dur = 0;
    for (const auto& q : scan->points) dur = std::max<double>(dur, q.t);
    const double t_ref = scan->stamp_s + 0.5 * dur;
    const auto a = interpolatePose(traj.stamps_s, traj.poses, scan->stamp_s);
    const auto b = interpolatePose(traj.stamps_s, traj.poses, scan->stamp_s + dur);
    const auto T = interpolatePose(traj.stamps_s, traj.poses, t_ref);
    if (!a || !b || !T) continue;
    deskewBetween(*scan, *a, *b, dur, *T);
    const Eigen::Isometry3d T_lidar_map = T->inverse();
    std::vector<std::vector<Eigen::Vector2d>> gt_v;
    for (const auto& l : curbs) {
      std::vector<Eigen::Vector2d> v;
      for (const auto& q : l) {
        if ((q.head<2>() - T->translation().head<2>()).norm() > 60) {  // runs near the vehicle only
          if (v.size() >= 2) gt_v.push_back(v);
          v.clear();
          continue;
        }
        v.push_back((T_lidar_map * Eigen::Vector3d(q.x(), q.y(), T->translation().z())).head<2>());
      }
      if (v.size() >= 2) gt_v.push_back(v);
    }
    auto onFace = [&](double x, double y) {
      const double yg = eval::lateralAt(gt_v, x, side, 15.0);
      return std::isfinite(yg) && std::abs(y - yg) <= face_tol_m;
    };
    std::set<int> gt_st, now_st, acc_st;
    for (int x = 5; x <= 30; ++x)
      if (std::isfinite(eval::lateralAt(gt_v, x, side, 15.0))) gt_st.insert(x);
    for (const auto& q : scan->points) {
      const double h = q.z + sensor_height_m;
      if (h < 0.02 || h > curb_h_m - 0.02 || !onFace(q.x, q.y)) continue;
      seen_map.push_back((*T * Eigen::Vector3d(q.x, q.y, q.z)).head<2>());
      if (q.x >= 4.5 && q.x < 30.5) now_st.insert(static_cast<int>(std::lround(q.x)));
    }
    std::set<int> behind, beyond;
    for (const auto& m : seen_map) {
      const Eigen::Vector3d v = T_lidar_map * Eigen::Vector3d(m.x(), m.y(), T->translation().z());
      if (!onFace(v.x(), v.y())) continue;
      const int st = static_cast<int>(std::lround(v.x()));
      if (v.x() >= 4.5 && v.x() < 30.5) acc_st.insert(st);
      if (st >= -10 && st < 5) behind.insert(st);
      if (st > 30 && st <= 45) beyond.insert(st);
    }
    if (gt_st.empty()) continue;
    auto cov = [&](const std::set<int>& s) {
      size_t n = 0;
      for (int x : s) n += gt_st.count(x);
      return static_cast<double>(n) / gt_st.size();
    };
    out.push_back({t_ref, cov(now_st), cov(acc_st), static_cast<int>(behind.size()), static_cast<int>(beyond.size())});
  }
  return out;
}

}  // namespace roadslam::boundary::test
