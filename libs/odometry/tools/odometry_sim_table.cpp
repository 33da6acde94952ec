// Prints the odometry's errors on every simulated scenario (or those named), one row each:
//   odometry_sim_table INI [DURATION_S] [SCENARIO.ini ...]
// With ODOMETRY_CAN_PRIOR=1 in the environment every frame gets the simulated car's CAN motion prior.
#include <cstdlib>
#include <cstdio>
#include <string>
#include <vector>

#include "../tests/sim_drive.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: odometry_sim_table CONFIG.ini [DURATION_S] [SCENARIO.ini ...]\n");
    return 2;
  }
  const auto params = roadslam::odometry::test::paramsFromIni(argv[1]);
  const double duration = argc > 2 ? std::stod(argv[2]) : 0.0;
  std::vector<std::string> scen;
  for (int i = 3; i < argc; ++i) scen.push_back(argv[i]);
  if (scen.empty()) {
    for (const char* n : {"urban-loop", "highway", "hills", "tunnel", "parking-lot", "parallel-streets"})
      scen.push_back(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/" + n + ".ini");
  }
  std::printf("%-40s %7s %7s %6s %6s %9s %8s %8s %8s\n", "scenario", "frames", "failed", "degen",
              "dist_m", "ATE_m", "RTE_%", "RRE_d/hm", "ms/frame");
  roadslam::odometry::test::SimDriveOptions options;
  const char* can = std::getenv("ODOMETRY_CAN_PRIOR");
  options.can_prior = can != nullptr && std::string(can) == "1";
  for (const auto& s : scen) {
    const auto r = roadslam::odometry::test::runSimDrive(s, duration, params, options);
    std::printf("%-40s %7zu %7zu %6zu %6.0f %9.3f %8.3f %8.3f %8.2f\n", s.substr(s.rfind('/') + 1).c_str(),
                r.frames, r.failed, r.degenerate, r.metrics.path_length_m, r.metrics.ate_rmse_m,
                r.metrics.rte_percent, r.metrics.rre_deg_per_100m, r.ms_mean);
    std::fflush(stdout);
  }
}
