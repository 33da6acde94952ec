// Place recognition on simulated drives with look-alike places, driven twice (laps = 2: the
// second lap revisits every place of the first, with the traffic elsewhere): Scan Context candidates
// (ring-key kd-tree, Kim & Kim 2018) for every keyframe, each verified by global registration (no guess)
// and, with the odometry check on, by the mapping's test of the correction against a drifted odometry
// (mapping::test::DriftModel defaults; LoopClosureParams place_consistency_*), against the simulator's ground
// truth. A revisit: an older keyframe (>= min_travel_m of path back) within 3 m (GT). An accepted loop is
// true when its measured relative pose is within 0.5 m / 2 deg of the GT one. Prints, per Scan Context
// distance threshold, recall (revisit keyframes with a true loop), precision (true / accepted), and the
// time per keyframe (descriptor + query) and per verification (thread CPU time, one thread).
//   taskset -c 1 build/bench/bench_place [--keyframe-m=2] [--laps=2]
#include <roadslam/mapping/loop_closure.h>
#include <roadslam/place/scan_context.h>
#include <roadslam/registration/global_registration.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <algorithm>

#include "sim_drive.h"

namespace {
namespace reg = roadslam::registration;
namespace pl = roadslam::place;

double cpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

struct Kf {
  reg::PointCloud points;
  Eigen::Isometry3d T_gt;
  Eigen::Isometry3d T_odo;  ///< drifted odometry, the graph's guess before any loop
  double path_m;
};

/// The mapping's acceptance test of a place candidate against the odometry (place_consistency_*).
bool consistent(const Kf& q, const Kf& m, const Eigen::Isometry3d& T_match_query, const roadslam::mapping::LoopClosureParams& lp) {
  const Eigen::Isometry3d corr = (m.T_odo.inverse() * q.T_odo).inverse() * T_match_query;
  const double path = q.path_m - m.path_m;
  return corr.translation().norm() <= lp.place_consistency_abs_m + lp.place_consistency_ratio * path &&
         Eigen::AngleAxisd(corr.linear()).angle() <= lp.place_consistency_rot_rad + lp.place_consistency_rot_rad_per_m * path;
}

struct Verified {
  double sc_distance;
  bool converged, consistent, right;
};

void run(const std::string& scenario, int laps, double keyframe_m) {
  auto p = roadslam::sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/" + scenario + ".ini");
  p.trajectory.laps = laps;
  const auto frames = roadslam::mapping::test::simulateDrive(p, {});
  std::vector<Kf> kfs;
  double path = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    if (i > 0) path += (frames[i].T_world_lidar_gt.translation() - frames[i - 1].T_world_lidar_gt.translation()).norm();
    if (!kfs.empty() && path - kfs.back().path_m < keyframe_m) continue;
    kfs.push_back({frames[i].points_lidar, frames[i].T_world_lidar_gt, frames[i].result.T_world_lidar, path});
  }
  const roadslam::mapping::LoopClosureParams lp;
  const std::vector<double> thresholds = {0.15, 0.2, 0.25, 0.3};
  pl::ScanContextParams sp = lp.place;
  sp.max_distance = thresholds.back();
  const reg::GlobalParams& gp = lp.global;
  pl::ScanContextDatabase db(sp);
  std::vector<bool> revisit(kfs.size(), false);
  std::vector<std::vector<Verified>> cands(kfs.size());
  double ms_sc = 0, ms_verify = 0;
  int verifications = 0;
  for (size_t q = 0; q < kfs.size(); ++q) {
    for (size_t j = 0; j < q && kfs[q].path_m - kfs[j].path_m >= sp.min_travel_m; ++j)
      if ((kfs[j].T_gt.translation() - kfs[q].T_gt.translation()).norm() <= 3.0) revisit[q] = true;
    const double t0 = cpuMs();
    pl::ScanContext sc = pl::makeScanContext(kfs[q].points, sp);
    const auto matches = db.query(sc, kfs[q].path_m, lp.max_candidates);
    ms_sc += cpuMs() - t0;
    for (const auto& m : matches) {
      const Eigen::Isometry3d gt = kfs[m.id].T_gt.inverse() * kfs[q].T_gt;
      const double t1 = cpuMs();
      const auto r = reg::alignGlobal(kfs[m.id].points, kfs[q].points, gp);
      ms_verify += cpuMs() - t1;
      ++verifications;
      const Eigen::Isometry3d E = gt.inverse() * r.T_target_source;
      const bool right = E.translation().norm() <= 0.5 && Eigen::AngleAxisd(E.linear()).angle() <= 2 * M_PI / 180;
      cands[q].push_back({m.distance, r.converged, consistent(kfs[q], kfs[m.id], r.T_target_source, lp), right});
    }
    db.add(q, kfs[q].path_m, std::move(sc));
  }
  const int revisits = static_cast<int>(std::count(revisit.begin(), revisit.end(), true));
  for (bool check : {false, true}) {
    for (double t : thresholds) {
      int found = 0, accepted = 0, right = 0;
      for (size_t q = 0; q < kfs.size(); ++q) {
        for (const auto& c : cands[q]) {
          if (c.sc_distance >= t) break;
          if (!c.converged || (check && !c.consistent)) continue;
          ++accepted;
          right += c.right ? 1 : 0;
          found += c.right && revisit[q] ? 1 : 0;
          break;  // the first accepted candidate closes the loop
        }
      }
      std::printf("| %-17s | %3s | %4.2f | %4zu | %4d | %4d | %6.1f %% | %4d / %4d | %6.1f %% | %5.2f | %5.1f |\n", scenario.c_str(),
                  check ? "on" : "off", t, kfs.size(), revisits, found, revisits ? 100.0 * found / revisits : 0.0, right,
                  accepted, accepted ? 100.0 * right / accepted : 100.0, ms_sc / std::max<size_t>(1, kfs.size()),
                  verifications ? ms_verify / verifications : 0.0);
    }
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  double keyframe_m = 2.0;
  int laps = 2;
  for (int a = 1; a < argc; ++a) {
    if (std::strncmp(argv[a], "--keyframe-m=", 13) == 0) keyframe_m = std::atof(argv[a] + 13);
    if (std::strncmp(argv[a], "--laps=", 7) == 0) laps = std::atoi(argv[a] + 7);
  }
  std::printf("| drive | odometry check | SC max distance | keyframes | revisit kfs | found | recall | true / accepted | precision | ms per kf (SC) | ms per verification |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const char* s : {"parallel-streets", "urban-loop"}) run(s, laps, keyframe_m);
  std::printf("keyframes every %.1f m of GT path, %d laps; Scan Context and global registration: LoopClosureParams defaults, "
              "at most %d candidates per keyframe.\n", keyframe_m, laps, roadslam::mapping::LoopClosureParams{}.max_candidates);
  return 0;
}
