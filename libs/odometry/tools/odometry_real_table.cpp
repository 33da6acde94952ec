// Prints the odometry's errors on the real LiDAR drives, one row each:
//   odometry_real_table CONFIG.ini [DIR POSES TIMES ...]
// Without folders: the KITTI drives in ../shared/data (raw 2011_09_26_0001 against its OXTS poses,
// odometry 00's first 16 sweeps against KITTI's reference moved into the velodyne frame). Extra
// drives are given as triples: a folder of .bin sweeps, LiDAR-frame poses (KITTI 3x4, one per
// sweep) and their times file. The ini's [odometry], [preprocess], [registration] and [kitti]
// sections are used, as roadslam-map would use them. With ODOMETRY_FRAMES=1 each frame's tilt and
// height error is printed too; ODOMETRY_STRIDE=K feeds every K-th sweep only (a drive K times as fast).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "roadslam/common/config.h"
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/eval/trajectory_metrics.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/sources/scan_source.h"

namespace fs = std::filesystem;
using namespace roadslam;

namespace {

struct Drive {
  std::string name, dir, poses, times;
  bool camera_frame_calib = false;  ///< poses are KITTI odometry camera poses (calib.txt beside)
};

std::vector<Drive> sharedDrives() {
  const std::string data = ROADSLAM_SHARED_DATA;
  std::vector<Drive> d;
  const std::string raw = data + "/kitti/raw-2011_09_26-0001";
  if (fs::exists(raw + "/velodyne.tar.zst")) {
    const std::string un = datasets::unpackTarZstOnce(raw + "/velodyne.tar.zst",
                                                      std::string(ROADSLAM_BINARY_DIR) + "/data/kitti-raw-0001");
    d.push_back({"kitti-raw-0001", un + "/velodyne", raw + "/poses_velo_kitti.txt", raw + "/times.txt"});
  } else {
    std::fprintf(stderr, "skipping KITTI raw 0001: %s/velodyne.tar.zst is absent\n", raw.c_str());
  }
  const std::string odo = data + "/kitti/odometry-00-first16";
  if (fs::exists(odo + "/velodyne/000015.bin")) {
    d.push_back({"kitti-odometry-00-first16", odo + "/velodyne", odo + "/poses_first16.txt", odo + "/times_first16.txt", true});
  }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || (argc - 2) % 3 != 0) {
    std::fprintf(stderr, "usage: odometry_real_table CONFIG.ini [DIR POSES TIMES ...]\n");
    return 2;
  }
  const auto cfg = loadIniFile(argv[1]);
  odometry::Params params;
  params.loadFromConfigFile(*cfg);
  std::vector<Drive> drives;
  for (int i = 2; i + 2 < argc; i += 3) drives.push_back({fs::path(argv[i]).filename().string(), argv[i], argv[i + 1], argv[i + 2]});
  if (drives.empty()) drives = sharedDrives();
  const size_t stride = std::getenv("ODOMETRY_STRIDE") ? std::stoul(std::getenv("ODOMETRY_STRIDE")) : 1;
  const bool verbose = std::getenv("ODOMETRY_FRAMES") && std::string(std::getenv("ODOMETRY_FRAMES")) == "1";
  std::printf("%-28s %6s %6s %6s %7s %8s %8s %8s %9s %9s %8s\n", "drive", "frames", "failed", "degen", "dist_m", "ATE_m",
              "RTE_%", "RRE_d/hm", "end_dz_m", "end_dpitch", "ms/frame");
  for (const auto& d : drives) {
    // the sweeps as roadslam-map reads them: one ScanSource, [kitti] and --times as there
    const auto source = sources::openScanSource(d.dir, *cfg, d.times);
    datasets::PoseList gt;
    if (d.camera_frame_calib) {
      const auto cam = datasets::readKittiTrajectory(d.poses, d.times);
      gt = datasets::cameraPosesToVelodyne(cam.poses,
                                           datasets::readKittiOdometryCalib(fs::path(d.poses).parent_path() / "calib.txt").T_cam0_velo);
    } else {
      gt = datasets::readKittiPoses(d.poses);
    }
    if (gt.size() != source->sizeHint()) {
      std::fprintf(stderr, "%s: %zu poses for %zu sweeps\n", d.name.c_str(), gt.size(), source->sizeHint());
      return 1;
    }
    odometry::Odometry odo(params);
    eval::MatchedTrajectories m;
    size_t failed = 0, degenerate = 0;
    double ms = 0;
    for (size_t i = 0; i < gt.size(); ++i) {
      auto next = source->next();
      if (!next) {
        std::fprintf(stderr, "%s: sweep %zu unreadable: %s\n", d.name.c_str(), i, source->errorMessage().c_str());
        return 1;
      }
      if (i % stride != 0) continue;
      Scan scan = std::move(*next);
      if (stride > 1) scan.stamp_s = 0.1 * static_cast<double>(i / stride);  // the same sweeps, K times as fast
      const auto r = odo.process(std::move(scan));
      ms += r.ms_total;
      if (r.status == odometry::FrameStatus::NotConverged || r.status == odometry::FrameStatus::Empty) ++failed;
      if (r.status == odometry::FrameStatus::Degenerate) ++degenerate;
      m.gt.push_back(gt[i]);
      m.est.push_back(r.T_world_lidar);
      if (verbose) {
        const Eigen::Isometry3d e = gt[i].inverse() * r.T_world_lidar;
        const Eigen::Vector3d ypr = e.rotation().eulerAngles(2, 1, 0);
        std::printf("  %3zu %-14s dz %7.3f m  pitch %7.3f deg  yaw %7.3f deg  it %2d  %s\n", i,
                    odometry::toString(r.status), (r.T_world_lidar.translation() - gt[i].translation()).z(),
                    std::remainder(ypr[1], M_PI) * 180 / M_PI, std::remainder(ypr[0], M_PI) * 180 / M_PI,
                    r.iterations, r.reason.c_str());
      }
    }
    const auto mt = eval::computeMetrics(m);
    const Eigen::Isometry3d end = m.gt.back().inverse() * m.est.back();
    const double end_pitch = std::asin(std::clamp(-end.rotation()(2, 0), -1.0, 1.0)) * 180 / M_PI;
    std::printf("%-28s %6zu %6zu %6zu %7.1f %8.3f %8.3f %8.3f %9.3f %9.3f %8.2f\n", d.name.c_str(), m.est.size(), failed, degenerate,
                mt.path_length_m, mt.ate_rmse_m, mt.rte_percent, mt.rre_deg_per_100m,
                (m.est.back().translation() - m.gt.back().translation()).z(), end_pitch,
                ms / static_cast<double>(m.est.size()));
    std::fflush(stdout);
  }
}
