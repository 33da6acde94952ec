// Global registration with no initial guess: keyframe pairs up to 10 m apart on the KITTI raw
// drive 2011_09_26_0001 (OXTS GT), the first 16 sweeps of KITTI odometry 00 (GT), and simulated VLP-16
// drives (urban loop, parallel streets: exact GT). Ours (FPFH + mutual matches + RANSAC + our ICP,
// GlobalParams defaults) and, with -DROADSLAM_BENCH_PEERS=ON, Open3D's FPFH + FGR + ICP on the same
// pairs in the same run; "features cached": the same pairs from features computed once per cloud (timed
// apart, "features of one cloud"), as a map or the loop closure keeps them per keyframe. Success: within 0.2 m and 1 deg of the GT relative pose. Time: process CPU
// time per pair, everything from the two sweeps to the pose (OpenMP pinned to one thread).
//   taskset -c 1 build/bench/bench_globalreg [--pairs-per-distance=N] [--sim-seconds=S]
#include <roadslam/datasets/kitti_scans.h>
#include <roadslam/datasets/trajectory_io.h>
#include <roadslam/registration/global_registration.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>

#include "globalreg_peers.h"
#include "sim_drive.h"

namespace {
namespace reg = roadslam::registration;
namespace ds = roadslam::datasets;

struct Drive {
  std::string name;
  std::vector<reg::PointCloud> clouds;  // lidar frame [m]
  std::vector<Eigen::Isometry3d> T_world_lidar;
};

double cpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

Drive kittiRaw() {
  Drive d{"kitti-raw-0001", {}, {}};
  const std::string raw = std::string(ROADSLAM_SHARED_DATA) + "/kitti/raw-2011_09_26-0001/";
  if (!std::filesystem::exists(raw + "velodyne.tar.zst")) return d;
  const ds::KittiScanFolder folder(ds::unpackTarZstOnce(raw + "velodyne.tar.zst", GLOBALREG_BENCH_CACHE) + "/velodyne");
  const ds::PoseList T = ds::readKittiPoses(raw + "poses_velo_kitti.txt");
  for (size_t i = 0; i < folder.size() && i < T.size(); ++i) {
    d.clouds.push_back(reg::toPointCloud(folder.read(i)));
    d.T_world_lidar.push_back(T[i]);
  }
  return d;
}

Drive kitti00() {
  Drive d{"kitti-odometry-00", {}, {}};
  const std::string seq = std::string(ROADSLAM_SHARED_DATA) + "/kitti/odometry-00-first16/";
  if (!std::filesystem::exists(seq + "calib.txt")) return d;
  const auto calib = ds::readKittiOdometryCalib(seq + "calib.txt");
  const auto T = ds::cameraPosesToVelodyne(ds::readKittiPoses(seq + "poses_first16.txt"), calib.T_cam0_velo);
  const ds::KittiScanFolder folder(seq + "velodyne");
  for (size_t i = 0; i < folder.size(); ++i) {
    d.clouds.push_back(reg::toPointCloud(folder.read(i)));
    d.T_world_lidar.push_back(T[i]);
  }
  return d;
}

// Simulated VLP-16 drive, sweeps deskewed with the true motion, one every >= 1 m (keyframes).
Drive simulated(const std::string& scenario, double seconds) {
  auto p = roadslam::sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/" + scenario + ".ini");
  p.duration_s = seconds;
  const auto frames = roadslam::mapping::test::simulateDrive(p, {});
  Drive d{"sim-" + scenario, {}, {}};
  for (const auto& f : frames) {
    if (!d.T_world_lidar.empty() && (f.T_world_lidar_gt.translation() - d.T_world_lidar.back().translation()).norm() < 1.0) continue;
    d.clouds.push_back(f.points_lidar);
    d.T_world_lidar.push_back(f.T_world_lidar_gt);
  }
  return d;
}

struct Pair {
  size_t i, j;
};
// For anchors spread over the drive, the sweep farthest within each of 2.5, 5, 7.5, 10 m.
std::vector<Pair> pairsOf(const Drive& d, int per_distance) {
  std::vector<Pair> out;
  const size_t n = d.clouds.size();
  const size_t step = std::max<size_t>(1, n / static_cast<size_t>(per_distance));
  for (double D : {2.5, 5.0, 7.5, 10.0}) {
    for (size_t i = 0; i < n; i += step) {
      size_t j = i;
      while (j + 1 < n && (d.T_world_lidar[j + 1].translation() - d.T_world_lidar[i].translation()).norm() <= D) ++j;
      if (j > i && (d.T_world_lidar[j].translation() - d.T_world_lidar[i].translation()).norm() > D - 2.5) out.push_back({i, j});
    }
  }
  return out;
}

struct Tally {
  int pairs = 0, ok = 0, converged = 0, wrong_converged = 0, ransac_ok = 0;
  std::vector<double> ms;
  void add(bool good, bool conv, bool pre_ok, double t) {
    ++pairs;
    ok += good && conv ? 1 : 0;
    converged += conv ? 1 : 0;
    wrong_converged += conv && !good ? 1 : 0;
    ransac_ok += pre_ok ? 1 : 0;
    ms.push_back(t);
  }
  double median() const {
    if (ms.empty()) return 0;
    auto v = ms;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  }
  double p90() const {
    if (ms.empty()) return 0;
    auto v = ms;
    std::sort(v.begin(), v.end());
    return v[static_cast<size_t>(0.9 * static_cast<double>(v.size() - 1))];
  }
};

bool within(const Eigen::Isometry3d& gt, const Eigen::Isometry3d& est) {
  const Eigen::Isometry3d E = gt.inverse() * est;
  return E.translation().norm() <= 0.2 && Eigen::AngleAxisd(E.linear()).angle() <= M_PI / 180.0;
}

void printRow(const std::string& drive, const std::string& method, const Tally& t, int ok_ref, bool has_conv) {
  const double n = std::max(1, t.pairs);
  auto percent = [](double x) {
    char b[32];
    std::snprintf(b, sizeof b, "%6.1f %%", x);
    return std::string(b);
  };
  const std::string ref = ok_ref < 0 ? "" : percent(100.0 * ok_ref / n);
  const std::string pre = ok_ref < 0 ? "" : percent(100.0 * t.ransac_ok / n);
  std::printf("| %-24s | %-22s | %5d | %6.1f %% | %s | %s | %s | %8.1f | %8.1f |\n", drive.c_str(), method.c_str(),
              t.pairs, 100.0 * t.ok / n, ref.c_str(), pre.c_str(),
              has_conv ? (std::to_string(t.converged) + " / " + std::to_string(t.wrong_converged)).c_str() : "  n/a  ",
              t.median(), t.p90());
}

}  // namespace

int main(int argc, char** argv) {
  const char* omp = std::getenv("OMP_NUM_THREADS");
  if (!omp || std::strcmp(omp, "1") != 0) {  // OpenMP (Open3D) reads it when its library loads
    setenv("OMP_NUM_THREADS", "1", 1);
    execv("/proc/self/exe", argv);
  }
  int per_distance = 12;
  double sim_s = 40;
  for (int a = 1; a < argc; ++a) {
    if (std::strncmp(argv[a], "--pairs-per-distance=", 21) == 0) per_distance = std::atoi(argv[a] + 21);
    if (std::strncmp(argv[a], "--sim-seconds=", 14) == 0) sim_s = std::atof(argv[a] + 14);
  }
  reg::GlobalParams prm;  // defaults; GLOBALREG_MAX_NEIGHBOURS / GLOBALREG_VOXEL override for parameter studies
  if (const char* v = std::getenv("GLOBALREG_MAX_NEIGHBOURS")) prm.max_feature_neighbours = std::atoi(v);
  if (const char* v = std::getenv("GLOBALREG_VOXEL")) prm.voxel_m = std::atof(v);
  if (const char* v = std::getenv("GLOBALREG_EPS")) prm.match_eps = std::atof(v);
  if (const char* v = std::getenv("GLOBALREG_FEATURE_RADIUS")) prm.feature_radius_m = std::atof(v);
  const char* only = std::getenv("GLOBALREG_ONLY");  // a drive name to run alone
  std::vector<std::function<Drive()>> drives = {kittiRaw, kitti00, [&] { return simulated("urban-loop", sim_s); },
                                                [&] { return simulated("parallel-streets", sim_s); }};
  std::printf("| drive | method | pairs | ok vs GT (0.2 m, 1 deg) | ok vs GT-seeded ICP | global stage ok | converged / wrong | median ms | p90 ms |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  Tally all_ours, all_o3d, all_ref, all_o3d_ref, all_cached, all_features;
  if (only && std::string(only) == "kitti-raw-0001") drives.resize(1);
  for (const auto& make : drives) {
    const Drive d = make();
    if (only && d.name != only) continue;
    if (d.clouds.size() < 2) {
      std::printf("| %s | (data missing) |\n", d.name.c_str());
      continue;
    }
    Tally ours, o3d, ours_ref, o3d_ref, cached;
    // features cached per cloud (as a map or the loop closure keeps them per keyframe): each cloud's once,
    // timed apart, then each pair from the two FeatureClouds
    const std::vector<Pair> pairs = pairsOf(d, per_distance);
    std::vector<std::unique_ptr<reg::FeatureCloud>> feats(d.clouds.size());
    std::vector<double> feature_ms;
    for (const Pair& p : pairs) {
      for (size_t k : {p.i, p.j}) {
        if (feats[k]) continue;
        const double t0 = cpuMs();
        feats[k] = std::make_unique<reg::FeatureCloud>(reg::computeFeatures(d.clouds[k], prm));
        feature_ms.push_back(cpuMs() - t0);
      }
    }
    int cached_same = 0;
    for (const Pair& p : pairs) {
      const Eigen::Isometry3d gt = d.T_world_lidar[p.i].inverse() * d.T_world_lidar[p.j];
      reg::GlobalDiagnostics diag;
      const double t0 = cpuMs();
      const reg::RegistrationResult r = reg::alignGlobal(d.clouds[p.i], d.clouds[p.j], prm, &diag);
      const double t1 = cpuMs();
      const reg::RegistrationResult rc = reg::alignGlobal(*feats[p.i], *feats[p.j], prm);
      const double t2 = cpuMs();
      cached.add(within(gt, rc.T_target_source), rc.converged, true, t2 - t1);
      all_cached.add(within(gt, rc.T_target_source), rc.converged, true, t2 - t1);
      cached_same += rc.status == r.status && rc.T_target_source.isApprox(r.T_target_source, 1e-9) ? 1 : 0;
      // the data's own answer: our ICP started at the GT pose (KITTI odometry 00's first sweeps disagree with
      // their GT by up to ~10 % of the motion: every method lands on the same pose, see docs/registration.md)
      const reg::Target ref_target(reg::voxelDownsample(d.clouds[p.i], prm.refine_voxel_m), prm.fine);
      const auto ref = reg::align(ref_target, reg::voxelDownsample(d.clouds[p.j], prm.refine_voxel_m), gt, prm.fine);
      const bool ok_ref = r.converged && within(ref.T_target_source, r.T_target_source);
      ours_ref.ok += ok_ref ? 1 : 0;
      all_ref.ok += ok_ref ? 1 : 0;
      ours.add(within(gt, r.T_target_source), r.converged, (gt.inverse() * diag.T_ransac).translation().norm() < 2.0, t1 - t0);
      all_ours.add(within(gt, r.T_target_source), r.converged, (gt.inverse() * diag.T_ransac).translation().norm() < 2.0, t1 - t0);
      if (std::getenv("GLOBALREG_VERBOSE")) {
        const Eigen::Isometry3d E = gt.inverse() * r.T_target_source;
        std::fprintf(stderr, "%s %zu-%zu %.1f m: %s conf %.2f corr %d cons %d rival %d err %.2f m %.2f deg %.0f ms (features %.0f match %.0f ransac %.0f refine %.0f)\n",
                     d.name.c_str(), p.i, p.j, gt.translation().norm(), reg::toString(r.status).c_str(), r.confidence,
                     diag.correspondences, diag.consensus, diag.rival_consensus, E.translation().norm(),
                     Eigen::AngleAxisd(E.linear()).angle() * 180 / M_PI, t1 - t0, diag.features_ms, diag.match_ms,
                     diag.ransac_ms, diag.refine_ms);
      }
      if (roadslam::bench::open3dAvailable()) {
        const double u0 = cpuMs();
        const auto g = roadslam::bench::open3dFpfhFgr(d.clouds[p.i], d.clouds[p.j]);
        const double u1 = cpuMs();
        const bool o3_ref = within(ref.T_target_source, g.T_target_source);
        o3d_ref.ok += o3_ref ? 1 : 0;
        all_o3d_ref.ok += o3_ref ? 1 : 0;
        o3d.add(within(gt, g.T_target_source), true, (gt.inverse() * g.T_fgr).translation().norm() < 2.0, u1 - u0);
        all_o3d.add(within(gt, g.T_target_source), true, (gt.inverse() * g.T_fgr).translation().norm() < 2.0, u1 - u0);
      }
    }
    printRow(d.name, "ours FPFH+RANSAC+ICP", ours, ours_ref.ok, true);
    printRow(d.name, "ours, features cached", cached, -1, true);
    Tally f;
    for (double t : feature_ms) f.add(true, true, true, t);
    all_features.ms.insert(all_features.ms.end(), feature_ms.begin(), feature_ms.end());
    std::printf("| %s | features of one cloud | %zu clouds | | | | | %8.1f | %8.1f |\n", d.name.c_str(), feature_ms.size(),
                f.median(), f.p90());
    std::printf("| %s | cached = from sweeps | %d of %zu pairs (same status and pose) | | | | | | |\n", d.name.c_str(),
                cached_same, pairs.size());
    if (roadslam::bench::open3dAvailable()) printRow(d.name, "open3d FPFH+FGR+ICP", o3d, o3d_ref.ok, false);
  }
  printRow("all", "ours FPFH+RANSAC+ICP", all_ours, all_ref.ok, true);
  printRow("all", "ours, features cached", all_cached, -1, true);
  std::printf("| all | features of one cloud | %zu clouds | | | | | %8.1f | %8.1f |\n", all_features.ms.size(),
              all_features.median(), all_features.p90());
  if (roadslam::bench::open3dAvailable()) printRow("all", "open3d FPFH+FGR+ICP", all_o3d, all_o3d_ref.ok, false);
  std::printf("\nok: converged and within 0.2 m / 1 deg of GT (open3d reports no convergence: every pose counts);\n"
              "ok vs GT-seeded ICP: converged and within 0.2 m / 1 deg of our ICP started at the GT pose (what the data says);\n"
              "global stage ok: the pose before ICP within 2 m; wrong: converged but outside 0.2 m / 1 deg.\n");
  std::printf("ours: GlobalParams defaults (voxel %.1f m, normals %.1f m, FPFH %.1f m, RANSAC <= %d draws, ICP at %.1f m)\n",
              prm.voxel_m, prm.normal_radius_m, prm.feature_radius_m, prm.ransac_max_iterations, prm.refine_voxel_m);
  std::printf("%s\n", roadslam::bench::open3dSettings().c_str());
  return 0;
}
