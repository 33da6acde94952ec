// The whole urban loop through the app's code path (about 100 s simulated, ~12 s of CPU): files,
// counts and the closed loop in the written ground truth. LABELS heavy.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "roadslam/sim/outputs.h"
#include "sim_test_util.h"

using namespace roadslam::sim;

TEST(SimFullDrive, UrbanLoopWritesAClosedLoop) {
  test::TempDir dir("full");
  Simulator sim(ScenarioParams::fromFile(test::iniPath("urban-loop.ini")));
  OutputOptions opt;
  opt.dir = dir.str();
  const RunReport rep = runToDirectory(sim, opt);
  const auto summary = nlohmann::json::parse(test::readAll(dir.str() + "/summary.json"));
  EXPECT_EQ(summary["packets"].get<uint64_t>(),
            static_cast<uint64_t>(std::floor(sim.duration_s() / LidarSimulator::packetPeriod_s())));
  EXPECT_NEAR(summary["distance_m"].get<double>(), 990.0, 20.0);
  EXPECT_EQ(summary["sweeps"].get<uint64_t>(), rep.stats.sweeps);
  EXPECT_GT(summary["points"].get<double>(), 0.6 * summary["rays"].get<double>());
  std::ifstream tum(dir.str() + "/gt_trajectory.tum");
  double t, x, y, z, qx, qy, qz, qw, x0 = 0, y0 = 0, path = 0, px = 0, py = 0;
  std::size_t n = 0;
  while (tum >> t >> x >> y >> z >> qx >> qy >> qz >> qw) {
    if (n == 0) { x0 = x; y0 = y; } else { path += std::hypot(x - px, y - py); }
    px = x; py = y;
    ++n;
  }
  EXPECT_GT(path, 950.0);
  EXPECT_LT(std::hypot(px - x0, py - y0), 3.0) << "the loop returns to its start";
  EXPECT_EQ(std::ifstream(dir.str() + "/velodyne.pcap", std::ios::ate | std::ios::binary).tellg(),
            static_cast<std::streamoff>(24 + rep.stats.data_packets * (16 + 42 + 1206) +
                                        rep.stats.position_packets * (16 + 42 + 512)));
}
