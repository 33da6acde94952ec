// sim::simulateOnce, the tests' shared drives: a finished folder is reused only for the scenario it
// was simulated from; under the same name a changed scenario (a new default in an ini) simulates again.
#include <gtest/gtest.h>

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
