// End-to-end: the shipped app on the real logs with the shipped vehicle inis; failures exit non-zero
// with one line naming the problem.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <sys/wait.h>
#include <filesystem>
#include <memory>
#include <string>

namespace {
const std::string kBin = ROADSLAM_CAN_BIN;
const std::string kData = ROADSLAM_SHARED_DATA;

struct AppRun {
  int status;
  std::string out;
};
AppRun run(const std::string& args) {
  const std::string cmd = kBin + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), p)) > 0) out.append(buf, n);
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}
}  // namespace

TEST(RoadslamCanApp, FailuresExitNonZeroWithOneLine) {
  for (const std::string args : {"decode --dbc /nonexistent.dbc x.log", "info /nonexistent.log", "bogus"}) {
    const AppRun r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << args << ": " << r.out;
    EXPECT_EQ(r.out.rfind("roadslam-can: ", 0), 0U) << r.out;
  }
  const std::string bad_dbc = ::testing::TempDir() + "/bad.dbc";
  const std::string log = ::testing::TempDir() + "/one.log";
  std::FILE* f = std::fopen(bad_dbc.c_str(), "w");
  std::fputs("BO_ 100 M: 8 X\n SG_ S : 7|16@2+ (1,0) [0|1] \"\" X\n", f);
  std::fclose(f);
  f = std::fopen(log.c_str(), "w");
  std::fputs("(1.000000) can0 064#0102030405060708\n", f);
  std::fclose(f);
  const AppRun r = run("decode --dbc " + bad_dbc + " " + log);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find("bad.dbc:2:15: byte order"), std::string::npos) << r.out;
}

TEST(RoadslamCanApp, CivicInfoReportsGapsAndOdometryRuns) {
  const std::string log = kData + "/can/civic-2019/civic_typeR_2019_turnonanddrive.candump.log";
  const std::string dbc = kData + "/can/civic-2019/honda_civic_hatchback_ex_2017_can_generated.dbc";
  if (!std::filesystem::exists(log)) GTEST_SKIP() << "missing " << log;
  AppRun r = run("info " + log + " --dbc " + dbc);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("28835 frames"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("largest gaps:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("1D0 "), std::string::npos);
  const std::string tum = ::testing::TempDir() + "/civic.tum";
  r = run("odometry --vehicle " + std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/honda-civic-2019.ini " + log +
          " --out " + tum + " --data-root " + kData);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("gaps"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(tum));
  EXPECT_TRUE(std::filesystem::exists(tum + ".ini"));
}
