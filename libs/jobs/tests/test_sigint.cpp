// Interruption: roadslam-map as a child process gets SIGINT about 1 s into a recording; it must stop
// between frames, exit with 130 and leave every output complete and readable.
#include <gtest/gtest.h>
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/maps/CSimpleMap.h>
#include <octomap/OcTree.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "sim_cache.h"

namespace fs = std::filesystem;
using namespace roadslam;

TEST(MapJobSigint, InterruptedRunLeavesConsistentOutputs) {
  const std::string exe = std::string(ROADSLAM_BINARY_DIR) + "/bin/roadslam-map";
  if (!fs::exists(exe)) GTEST_SKIP() << exe << " not built";
  const std::string sim_dir = jobs::test::simulateOnce(jobs::test::smallLoop());
  const std::string out = std::string(ROADSLAM_BINARY_DIR) + "/test-out/map-job-sigint";
  fs::remove_all(out);
  const std::string cfg = std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini";
  const std::string pcap = sim_dir + "/velodyne.pcap";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    execl(exe.c_str(), exe.c_str(), "--config", cfg.c_str(), "--input", pcap.c_str(), "--out", out.c_str(), "--quiet",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  EXPECT_EQ(WEXITSTATUS(status), 130);

  std::ifstream sf(out + "/summary.json");
  const auto summary = nlohmann::json::parse(sf);
  EXPECT_TRUE(summary["interrupted"].get<bool>());
  const size_t frames = summary["frames"].get<size_t>();
  EXPECT_GT(frames, 0u);
  EXPECT_LT(frames, 500u) << "the run was not interrupted early";
  for (const char* f : {"trajectory.tum", "trajectory_odometry.tum", "trajectory_kitti.txt", "frames.csv",
                        "config_used.ini", "map.ply", "map.pcd", "grid.png", "grid.yaml", "grid.gridmap",
                        "map_top.png"}) {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  }
  octomap::OcTree tree(0.1);
  EXPECT_TRUE(tree.readBinary(out + "/map.bt"));
  mrpt::maps::CSimpleMap sm;
  ASSERT_TRUE(sm.loadFromFile(out + "/keyframes.simplemap"));
  EXPECT_EQ(sm.size(), summary["keyframes"].get<size_t>());
  mrpt::graphs::CNetworkOfPoses3DInf g;
  g.loadFromTextFile(out + "/posegraph.graph");
  EXPECT_EQ(g.nodeCount(), sm.size());
  std::ifstream tum(out + "/trajectory.tum");
  size_t lines = 0;
  for (std::string l; std::getline(tum, l);) lines += (!l.empty() && l[0] != '#') ? 1 : 0;
  EXPECT_EQ(lines, frames);
  for (const auto& e : fs::directory_iterator(out)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "left behind: " << e.path();
  }
}
