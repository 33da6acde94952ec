// sim::simulateOnce, the tests' shared drives: a finished folder is reused only for the scenario it
// was simulated from; under the same name a changed scenario (a new default in an ini) simulates again;
// two processes wanting the same drive at once simulate it once. sim::cachedDriveDir names a folder per
// scenario.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "roadslam/sim/outputs.h"
#include "sim_test_util.h"

using namespace roadslam;
using namespace roadslam::sim;

namespace {

std::string fileText(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

ScenarioParams shortDrive(int moving_cars) {
  ScenarioParams p = ScenarioParams::fromFile(test::iniPath("urban-loop.ini"));
  p.duration_s = 0.2;
  p.world.moving_cars = moving_cars;
  return p;
}

}  // namespace

TEST(SimulateOnce, ReusesTheFolderOnlyForItsOwnScenario) {
  test::TempDir tmp("simonce");
  const std::string dir = tmp.str() + "/drive";
  ASSERT_EQ(simulateOnce(shortDrive(2), dir), dir);
  const std::string gt2 = fileText(dir + "/gt_objects.json");
  ASSERT_FALSE(gt2.empty());
  // the same scenario: the folder as it is (a mark left in it survives)
  { std::ofstream(dir + "/mark") << "x"; }
  simulateOnce(shortDrive(2), dir);
  EXPECT_TRUE(std::filesystem::exists(dir + "/mark"));
  // another scenario under the same name: simulated again, the old folder gone
  simulateOnce(shortDrive(3), dir);
  EXPECT_FALSE(std::filesystem::exists(dir + "/mark"));
  const std::string gt3 = fileText(dir + "/gt_objects.json");
  EXPECT_NE(gt3, gt2);
  EXPECT_NE(fileText(dir + "/.complete").find("moving_cars"), std::string::npos);
  for (const auto& e : std::filesystem::directory_iterator(tmp.path)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
}

// Two test processes (ctest -j2) asking for the same drive at once: one simulates it, the other waits on
// the lock and reuses the folder. The parent holds the lock while both children start, so both are
// waiting when it is released (without the lock both would simulate).
TEST(SimulateOnce, TwoProcessesAtOnceSimulateTheDriveOnce) {
  test::TempDir tmp("simonce_parallel");
  const std::string dir = tmp.str() + "/drive";
  const int fd = ::open((dir + ".lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  pid_t child[2];
  for (pid_t& c : child) {
    c = ::fork();
    ASSERT_GE(c, 0);
    if (c == 0) {
      ::close(fd);  // the parent's lock is on this inherited descriptor too: only the parent's close frees it
      bool simulated = false;
      try {
        simulateOnce(shortDrive(2), dir, &simulated);
      } catch (...) {
        ::_exit(3);
      }
      ::_exit(simulated ? 1 : 0);
    }
  }
  ::usleep(300000);  // both children are at the lock (a late one finds the folder finished: the same count)
  ::close(fd);
  int simulations = 0;
  for (const pid_t c : child) {
    int status = 0;
    ASSERT_EQ(::waitpid(c, &status, 0), c);
    ASSERT_TRUE(WIFEXITED(status));
    ASSERT_LE(WEXITSTATUS(status), 1) << "simulateOnce threw in a child";
    simulations += WEXITSTATUS(status);
  }
  EXPECT_EQ(simulations, 1);
  EXPECT_EQ(fileText(dir + "/.complete").empty(), false);
  bool simulated = true;
  simulateOnce(shortDrive(2), dir, &simulated);
  EXPECT_FALSE(simulated) << "the finished folder is reused";
}

TEST(SimulateOnce, CachedDriveDirIsOnePerScenario) {
  const std::string a = cachedDriveDir(shortDrive(2), "/c");
  EXPECT_EQ(a, cachedDriveDir(shortDrive(2), "/c"));
  EXPECT_NE(a, cachedDriveDir(shortDrive(3), "/c"));
  EXPECT_EQ(a.rfind("/c/" + shortDrive(2).name + "-0.2s-", 0), 0u) << a;
  EXPECT_EQ(a.size(), std::string("/c/" + shortDrive(2).name + "-0.2s-").size() + 16) << a;
  ScenarioParams whole = shortDrive(2);
  whole.duration_s = 0;
  EXPECT_NE(cachedDriveDir(whole, "/c").find("-full-"), std::string::npos);
}
