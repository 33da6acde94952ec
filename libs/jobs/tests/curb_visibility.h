#pragma once
// Oracle for the simulated drives: how much of a ground-truth curb is in view at all, independent of
// the detector. A return counts as "on the curb face" when it lies within face_tol_m of the GT curb
// line and between the road and the curb top (flat drives: the road is sensor_height below the
// lidar). Per sweep and side: the fraction of the 1 m stations 5-30 m ahead (where the GT curb
// exists; the eval's default axis stations) holding such a return in this sweep, and in all sweeps
// so far (map frame, GT poses). A side "observable" in a sweep (accum >= 0.5) is one a detector
// without prediction can report over the half of the stations the eval asks for; the fraction of
// sweeps with both sides observable is the ceiling of such a detector.
#include <cmath>
#include <set>
#include <string>
#include <unordered_map>
#include <vector>

#include "roadslam/common/pose_interpolation.h"
#include "roadslam/odometry/deskew.h"
#include "roadslam/common/config.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/eval/boundary_metrics.h"
#include "roadslam/sources/scan_source.h"

namespace roadslam::jobs::bounds_test {

struct CurbView {
  double stamp_s = 0;            ///< reference time of the sweep [s]
  double sweep = 0, accum = 0;   ///< station coverage 5-30 m ahead, this sweep / all sweeps so far [-]
  int behind = 0, beyond = 0;    ///< stations -10..5 m / 30..45 m with face returns, all sweeps so far [-]
  bool gt = false;               ///< the GT curb exists at some station 5-30 m ahead [-]
};

/// Both sides of one sweep (index 0 left, 1 right).
struct SweepView {
  double stamp_s = 0;  ///< reference time of the sweep [s]
  CurbView side[2];
  bool observable() const { return side[0].gt && side[1].gt && side[0].accum >= 0.5 && side[1].accum >= 0.5; }
};

/// Per sweep, both sides in one pass over the drive (flat drives: the road lies sensor_height_m below
/// the lidar). Face returns of past sweeps are kept one per 0.1 m map cell.
inline std::vector<SweepView> curbVisibilityBoth(const std::string& drive, const std::string& ini,
                                                 double sensor_height_m = 1.9, double curb_h_m = 0.15,
                                                 double face_tol_m = 0.15) {
  const auto cfg = loadIniFile(ini);
  auto stream = sources::openScanSource(drive + "/velodyne.pcap", *cfg);
  const auto traj = datasets::readTum(drive + "/gt_trajectory.tum");
  const auto curbs = eval::readGtCurbs(drive + "/gt_boundaries.json");
  std::unordered_map<int64_t, Eigen::Vector2d> seen_map;  // face returns of all sweeps so far, map frame
  auto key = [](const Eigen::Vector2d& m) {
    return (static_cast<int64_t>(std::floor(m.x() / 0.1)) << 32) ^ (static_cast<int64_t>(std::floor(m.y() / 0.1)) & 0xffffffffLL);
  };
  std::vector<SweepView> out;
  while (auto scan = stream->next()) {
    double dur = 0;
    for (const auto& q : scan->points) dur = std::max<double>(dur, q.t);
    const double t_ref = scan->stamp_s + 0.5 * dur;
    const auto a = interpolatePose(traj.stamps_s, traj.poses, scan->stamp_s);
    const auto b = interpolatePose(traj.stamps_s, traj.poses, scan->stamp_s + dur);
    const auto T = interpolatePose(traj.stamps_s, traj.poses, t_ref);
    if (!a || !b || !T) continue;
    odometry::deskewBetween(*scan, *a, *b, dur, *T);
    const Eigen::Isometry3d T_lidar_map = T->inverse();
    const Eigen::Vector2d c = T->translation().head<2>();
    std::vector<std::vector<Eigen::Vector2d>> gt_v;
    for (const auto& l : curbs) {
      std::vector<Eigen::Vector2d> v;
      for (const auto& q : l) {
        if ((q.head<2>() - c).norm() > 60) {  // runs near the vehicle only
          if (v.size() >= 2) gt_v.push_back(v);
          v.clear();
          continue;
        }
        v.push_back((T_lidar_map * Eigen::Vector3d(q.x(), q.y(), T->translation().z())).head<2>());
      }
      if (v.size() >= 2) gt_v.push_back(v);
    }
    // The side whose GT curb this vehicle-frame point lies on (+1 / -1), 0 for none.
    auto faceSide = [&](double x, double y) {
      const int s = y > 0 ? 1 : -1;
      const double yg = eval::lateralAt(gt_v, x, s, 15.0);
      return std::isfinite(yg) && std::abs(y - yg) <= face_tol_m ? s : 0;
    };
    SweepView sv;
    sv.stamp_s = t_ref;
    std::set<int> gt_st[2], now_st[2], acc_st[2], behind[2], beyond[2];
    for (int k = 0; k < 2; ++k)
      for (int x = 5; x <= 30; ++x)
        if (std::isfinite(eval::lateralAt(gt_v, x, k == 0 ? 1 : -1, 15.0))) gt_st[k].insert(x);
    for (const auto& q : scan->points) {
      const double h = q.z + sensor_height_m;
      if (h < 0.02 || h > curb_h_m - 0.02) continue;
      const int s = faceSide(q.x, q.y);
      if (s == 0) continue;
      const Eigen::Vector2d m = (*T * Eigen::Vector3d(q.x, q.y, q.z)).head<2>();
      seen_map.emplace(key(m), m);
      if (q.x >= 4.5 && q.x < 30.5) now_st[s > 0 ? 0 : 1].insert(static_cast<int>(std::lround(q.x)));
    }
    for (const auto& [k, m] : seen_map) {
      if ((m - c).norm() > 50) continue;
      const Eigen::Vector3d v = T_lidar_map * Eigen::Vector3d(m.x(), m.y(), T->translation().z());
      if (v.x() < -10.5 || v.x() > 45.5) continue;
      const int s = faceSide(v.x(), v.y());
      if (s == 0) continue;
      const int i = s > 0 ? 0 : 1, st = static_cast<int>(std::lround(v.x()));
      if (v.x() >= 4.5 && v.x() < 30.5) acc_st[i].insert(st);
      if (st >= -10 && st < 5) behind[i].insert(st);
      if (st > 30 && st <= 45) beyond[i].insert(st);
    }
    for (int i = 0; i < 2; ++i) {
      auto cov = [&](const std::set<int>& s) {
        size_t n = 0;
        for (int x : s) n += gt_st[i].count(x);
        return gt_st[i].empty() ? 0.0 : static_cast<double>(n) / gt_st[i].size();
      };
      sv.side[i] = {t_ref, cov(now_st[i]), cov(acc_st[i]), static_cast<int>(behind[i].size()),
                    static_cast<int>(beyond[i].size()), !gt_st[i].empty()};
    }
    out.push_back(sv);
  }
  return out;
}

/// One side (+1 left, -1 right) of curbVisibilityBoth, sweeps where that GT side exists.
inline std::vector<CurbView> curbVisibility(const std::string& drive, const std::string& ini, int side,
                                            double sensor_height_m = 1.9, double curb_h_m = 0.15,
                                            double face_tol_m = 0.15) {
  std::vector<CurbView> out;
  for (const auto& s : curbVisibilityBoth(drive, ini, sensor_height_m, curb_h_m, face_tol_m))
    if (s.side[side > 0 ? 0 : 1].gt) out.push_back(s.side[side > 0 ? 0 : 1]);
  return out;
}

}  // namespace roadslam::jobs::bounds_test
