// Memory of the odometry over a long simulated drive: the resident set and the local map, sampled
// every N frames, must level off once the map radius is filled (the target: "memory bounded
// on an hour-long simulated drive"). The urban loop at 36 laps is about an hour (36 km).
//   odometry_memory CONFIG.ini SCENARIO.ini LAPS [EVERY_FRAMES]
// The harness itself keeps two poses per frame for the final error (~0.25 kB per frame, ~9 MB an hour).
#include <cstdio>
#include <fstream>
#include <string>

#include "../tests/sim_drive.h"

namespace {
/// VmRSS or VmHWM of this process [MiB] (proc(5)).
double procStatusMiB(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind(key, 0) == 0) return std::stod(line.substr(line.find(':') + 1)) / 1024.0;
  }
  return 0.0;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: odometry_memory CONFIG.ini SCENARIO.ini LAPS [EVERY_FRAMES]\n");
    return 2;
  }
  namespace t = roadslam::odometry::test;
  const auto params = t::paramsFromIni(argv[1]);
  t::SimDriveOptions options;
  options.laps = std::stoi(argv[3]);
  const size_t every = argc > 4 ? std::stoul(argv[4]) : 1000;
  std::printf("%8s %9s %9s %9s %11s %10s\n", "frame", "time_s", "rss_MiB", "peak_MiB", "map_voxels", "ms/frame");
  double ms_sum = 0, t0 = -1;
  size_t n = 0;
  options.on_frame = [&](const roadslam::odometry::FrameResult& f, const roadslam::odometry::Odometry& odo) {
    if (t0 < 0) t0 = f.stamp_s;
    ms_sum += f.ms_total;
    if (++n % every) return;
    std::printf("%8zu %9.0f %9.1f %9.1f %11zu %10.2f\n", n, f.stamp_s - t0, procStatusMiB("VmRSS"),
                procStatusMiB("VmHWM"), odo.matcher().mapSize(), ms_sum / every);
    std::fflush(stdout);
    ms_sum = 0;
  };
  const auto r = t::runSimDrive(argv[2], 0.0, params, options);
  std::printf("frames %zu, failed %zu, path %.0f m, ATE %.3f m, RTE %.3f %%, RRE %.3f deg/100 m, peak RSS %.1f MiB\n",
              r.frames, r.failed, r.metrics.path_length_m, r.metrics.ate_rmse_m, r.metrics.rte_percent,
              r.metrics.rre_deg_per_100m, procStatusMiB("VmHWM"));
}
