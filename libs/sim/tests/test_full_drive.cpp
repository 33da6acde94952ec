// The whole urban loop through the app's code path (about 100 s simulated, ~18 s of CPU): files,
// counts and the closed loop in the written ground truth. The drive is the build tree's cached one
// (sim::simulateCached), the same folder the heavy map and bounds jobs read: simulated once for all
// of them. LABELS heavy.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "roadslam/sim/outputs.h"
#include "sim_test_util.h"

using namespace roadslam::sim;

TEST(SimFullDrive, UrbanLoopWritesAClosedLoop) {
  const ScenarioParams p = ScenarioParams::fromFile(test::iniPath("urban-loop.ini"));
  const std::string dir = simulateCached(p, ROADSLAM_SIM_CACHE);
  const Simulator sim(p);
  const auto summary = nlohmann::json::parse(test::readAll(dir + "/summary.json"));
  const auto data_packets = summary["packets"].get<uint64_t>();
  const auto position_packets = summary["position_packets"].get<uint64_t>();
  EXPECT_EQ(data_packets, static_cast<uint64_t>(std::floor(sim.duration_s() / LidarSimulator::packetPeriod_s())));
  EXPECT_NEAR(summary["distance_m"].get<double>(), 990.0, 20.0);
  // 600 rpm: one sweep per 0.1 s
  EXPECT_NEAR(static_cast<double>(summary["sweeps"].get<uint64_t>()), sim.duration_s() * 10.0, 1.0);
  EXPECT_GT(summary["points"].get<double>(), 0.6 * summary["rays"].get<double>());
  std::ifstream tum(dir + "/gt_trajectory.tum");
  double t, x, y, z, qx, qy, qz, qw, x0 = 0, y0 = 0, path = 0, px = 0, py = 0;
  std::size_t n = 0;
  while (tum >> t >> x >> y >> z >> qx >> qy >> qz >> qw) {
    if (n == 0) { x0 = x; y0 = y; } else { path += std::hypot(x - px, y - py); }
    px = x; py = y;
    ++n;
  }
  EXPECT_GT(path, 950.0);
  EXPECT_LT(std::hypot(px - x0, py - y0), 3.0) << "the loop returns to its start";
  // pcap file header, then per packet its record header, UDP/IP/Ethernet headers and payload
  EXPECT_EQ(std::ifstream(dir + "/velodyne.pcap", std::ios::ate | std::ios::binary).tellg(),
            static_cast<std::streamoff>(24 + data_packets * (16 + 42 + 1206) + position_packets * (16 + 42 + 512)));
}
