// Place recognition (issue 22) on simulated drives with look-alike places: Scan Context candidates (ring-key
// kd-tree, Kim & Kim 2018) for every keyframe, each verified by global registration (no guess) before it
// counts, against the simulator's ground truth. A revisit: an older keyframe (>= min_travel_m of path back)
// within 3 m (GT). An accepted loop is true when its measured relative pose is within 0.5 m / 2 deg of the GT
// one. Prints recall (revisit keyframes with a true loop), precision, false candidates stopped by the
// verification, and time per keyframe (descriptor + query) and per verification (CPU, one thread).
//   taskset -c 1 build/bench/bench_place [--keyframe-m=2] [--seconds=0 (whole drive)]
#include <roadslam/mapping/loop_closure.h>
#include <roadslam/place/scan_context.h>
#include <roadslam/registration/global_registration.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>

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
  Eigen::Isometry3d T_odo;  ///< drifted odometry (test::DriftModel defaults), the graph's guess before any loop
  double path_m;
};

/// The mapping's acceptance test of a place candidate against the odometry (LoopClosureParams place_consistency_*).
bool consistent(const Kf& q, const Kf& m, const Eigen::Isometry3d& T_match_query, const roadslam::mapping::LoopClosureParams& lp) {
  const Eigen::Isometry3d corr = (m.T_odo.inverse() * q.T_odo).inverse() * T_match_query;
  const double path = q.path_m - m.path_m;
  return corr.translation().norm() <= lp.place_consistency_abs_m + lp.place_consistency_ratio * path &&
         Eigen::AngleAxisd(corr.linear()).angle() <= lp.place_consistency_rot_rad + lp.place_consistency_rot_rad_per_m * path;
}

void run(const std::string& scenario, double seconds, double keyframe_m, bool check_odometry) {
  const roadslam::mapping::LoopClosureParams lp;
  auto p = roadslam::sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/" + scenario + ".ini");
  p.duration_s = seconds;
  const auto frames = roadslam::mapping::test::simulateDrive(p, {});
  std::vector<Kf> kfs;
  double path = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    if (i > 0) path += (frames[i].T_world_lidar_gt.translation() - frames[i - 1].T_world_lidar_gt.translation()).norm();
    if (!kfs.empty() && path - kfs.back().path_m < keyframe_m) continue;
    kfs.push_back({frames[i].points_lidar, frames[i].T_world_lidar_gt, frames[i].result.T_world_lidar, path});
  }
  pl::ScanContextParams sp;
  if (const char* v = std::getenv("PLACE_MAX_DISTANCE")) sp.max_distance = std::atof(v);
  const reg::GlobalParams gp;
  pl::ScanContextDatabase db(sp);
  int revisits = 0, found = 0, accepted = 0, true_acc = 0, candidates = 0, false_cand_stopped = 0;
  double ms_sc = 0, ms_verify = 0;
  int verifications = 0;
  for (size_t q = 0; q < kfs.size(); ++q) {
    bool revisit = false;
    size_t nearest = 0;
    double nearest_m = 1e9;
    for (size_t j = 0; j < q && kfs[q].path_m - kfs[j].path_m >= sp.min_travel_m; ++j) {
      const double dj = (kfs[j].T_gt.translation() - kfs[q].T_gt.translation()).norm();
      revisit |= dj <= 3.0;
      if (dj < nearest_m) {
        nearest_m = dj;
        nearest = j;
      }
    }
    revisits += revisit ? 1 : 0;
    const double t0 = cpuMs();
    pl::ScanContext sc = pl::makeScanContext(kfs[q].points, sp);
    const auto matches = db.query(sc, kfs[q].path_m, 2);
    ms_sc += cpuMs() - t0;
    bool got = false;
    for (const auto& m : matches) {
      ++candidates;
      const Eigen::Isometry3d gt = kfs[m.id].T_gt.inverse() * kfs[q].T_gt;
      const double t1 = cpuMs();
      const auto r = reg::alignGlobal(kfs[m.id].points, kfs[q].points, gp);
      ms_verify += cpuMs() - t1;
      ++verifications;
      const Eigen::Isometry3d E = gt.inverse() * r.T_target_source;
      const bool right = E.translation().norm() <= 0.5 && Eigen::AngleAxisd(E.linear()).angle() <= 2 * M_PI / 180;
      const bool near = gt.translation().norm() <= 10.0;
      if (!r.converged || (check_odometry && !consistent(kfs[q], kfs[m.id], r.T_target_source, lp))) {
        false_cand_stopped += near ? 0 : 1;
        continue;
      }
      ++accepted;
      true_acc += right ? 1 : 0;
      if (!right)
        std::fprintf(stderr, "  %s false loop kf %zu -> %zu: GT %.1f m apart, err %.2f m, conf %.2f, sc %.3f\n", scenario.c_str(),
                     q, m.id, gt.translation().norm(), E.translation().norm(), r.confidence, m.distance);
      got |= right && revisit;
      break;  // the first accepted candidate closes the loop
    }
    found += got ? 1 : 0;
    if (revisit && std::getenv("PLACE_VERBOSE")) {
      int shift = 0;
      const double d = pl::scanContextDistance(sc, db.descriptor(nearest), &shift);
      std::fprintf(stderr, "  %s revisit kf %zu: true kf %zu %.1f m, SC distance %.3f, matches %zu%s\n", scenario.c_str(), q,
                   nearest, nearest_m, d, matches.size(), got ? " found" : "");
    }
    db.add(q, kfs[q].path_m, std::move(sc));
  }
  std::printf("| %-18s | %-3s | %4zu | %5d | %5d | %6.1f %% | %5d / %5d | %6.1f %% | %5d | %6.2f | %6.1f |\n", scenario.c_str(), check_odometry ? "on" : "off", kfs.size(),
              revisits, found, revisits ? 100.0 * found / revisits : 0.0, true_acc, accepted,
              accepted ? 100.0 * true_acc / accepted : 100.0, false_cand_stopped, ms_sc / std::max<size_t>(1, kfs.size()),
              verifications ? ms_verify / verifications : 0.0);
}

}  // namespace

int main(int argc, char** argv) {
  double keyframe_m = 2.0, seconds = 0;
  for (int a = 1; a < argc; ++a) {
    if (std::strncmp(argv[a], "--keyframe-m=", 13) == 0) keyframe_m = std::atof(argv[a] + 13);
    if (std::strncmp(argv[a], "--seconds=", 10) == 0) seconds = std::atof(argv[a] + 10);
  }
  std::printf("| drive | odometry check | keyframes | revisit kfs | found | recall | true / accepted | precision | far candidates stopped | ms per kf (SC) | ms per verification |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const char* s : {"parallel-streets", "urban-loop"})
    for (bool check : {false, true}) run(s, seconds, keyframe_m, check);
  std::printf("keyframes every %.1f m of GT path; Scan Context and global registration defaults ([loop_closure_place], "
              "[loop_closure_global]).\n", keyframe_m);
  return 0;
}
