// The roadslam-grab executable under SIGINT (clean stop: complete rawlog) and SIGKILL (rawlog
// readable up to the last sync flush: at most about a second lost).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <cstdlib>

#include <nlohmann/json.hpp>

#include "grab_test_util.h"
#include "roadslam/pcap/pcap_reader.h"

using namespace roadslam;
using namespace roadslam::grabber;

namespace {

uint16_t freeUdpPort() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a));
  socklen_t len = sizeof(a);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(fd);
  return ntohs(a.sin_port);
}

struct GrabProcess {
  pid_t pid = -1;
  uint16_t data_port = 0, position_port = 0;
  std::string out;

  explicit GrabProcess(const std::string& dir) : out(dir + "/session") {
    data_port = freeUdpPort();
    do position_port = freeUdpPort();
    while (position_port == data_port);
    // The test's own ini variant, written into the build dir.
    const std::string ini = std::string(ROADSLAM_BINARY_DIR) + "/grab_kill_" + std::to_string(::getpid()) + "_" +
                            std::to_string(data_port) + ".ini";
    std::ofstream(ini) << "[grab]\nsensors = lidar\nflush_period_ms = 500\nreorder_window_ms = 300\n"
                          "status_period_ms = 500\n[lidar]\nmodel = vlp16\ndata_port = "
                       << data_port << "\nposition_port = " << position_port << "\n";
    const std::string exe = std::string(ROADSLAM_BINARY_DIR) + "/bin/roadslam-grab";
    const std::string log = dir + "/grab.log";
    pid = ::fork();
    if (pid == 0) {
      if (!std::freopen(log.c_str(), "w", stderr) || !std::freopen(log.c_str(), "a", stdout)) ::_exit(126);
      ::execl(exe.c_str(), exe.c_str(), "--config", ini.c_str(), "--out", out.c_str(), "--duration", "60",
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // Listening once the session files exist (written after the sockets are bound).
    for (int i = 0; i < 200 && !std::filesystem::exists(out + "/params_used.ini"); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    std::filesystem::remove(ini);
  }
  /// Exit status after \p sig, or -1 when it did not end within 10 s.
  int signalAndWait(int sig) {
    ::kill(pid, sig);
    for (int i = 0; i < 400; ++i) {
      int status = 0;
      if (::waitpid(pid, &status, WNOHANG) == pid) {
        pid = -1;
        return status;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(25));
    }
    return -1;
  }
  ~GrabProcess() {
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
};

}  // namespace

class GrabStopSignal : public ::testing::TestWithParam<int> {};

TEST_P(GrabStopSignal, FlushesAndClosesACompleteRawlog) {
  if (!std::filesystem::exists(std::string(ROADSLAM_BINARY_DIR) + "/bin/roadslam-grab"))
    GTEST_SKIP() << "bin/roadslam-grab not built";
  const auto& pkts = test::simPackets(1.5);
  test::TempDir dir("stop" + std::to_string(GetParam()));
  GrabProcess grab(dir.str());
  ASSERT_TRUE(std::filesystem::exists(grab.out + "/params_used.ini")) << test::readAll(dir.str() + "/grab.log");
  const std::size_t sent = test::sendPaced(pkts, grab.data_port, grab.position_port, 1.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const int status = grab.signalAndWait(GetParam());
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 0) << test::readAll(dir.str() + "/grab.log");
  std::string error;
  const auto recorded = test::readRawlog(grab.out + "/grab_000.rawlog", nullptr, &error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_TRUE(recorded == test::dataPayloads(pkts)) << recorded.size() << " packets recorded";
  const auto summary = nlohmann::json::parse(test::readAll(grab.out + "/summary.json"));
  EXPECT_EQ(summary["packets_received"].get<std::size_t>(), sent);
  EXPECT_EQ(summary["packets_dropped"].get<std::size_t>(), 0u);
  EXPECT_TRUE(std::filesystem::exists(grab.out + "/grab.ini"));
}

INSTANTIATE_TEST_SUITE_P(Signals, GrabStopSignal, ::testing::Values(SIGINT, SIGTERM),
                         [](const auto& info) { return info.param == SIGINT ? "SIGINT" : "SIGTERM"; });

TEST(GrabKill, SigkillLosesAtMostAboutOneSecond) {
  if (!std::filesystem::exists(std::string(ROADSLAM_BINARY_DIR) + "/bin/roadslam-grab"))
    GTEST_SKIP() << "bin/roadslam-grab not built";
  const auto& pkts = test::simPackets(3.0);
  const auto expected = test::dataPayloads(pkts);
  test::TempDir dir("sigkill");
  GrabProcess grab(dir.str());
  ASSERT_TRUE(std::filesystem::exists(grab.out + "/params_used.ini")) << test::readAll(dir.str() + "/grab.log");
  std::atomic<std::size_t> progress{0};
  std::thread tx([&] { test::sendPaced(pkts, grab.data_port, grab.position_port, 1.0, "127.0.0.1", &progress); });
  std::this_thread::sleep_for(std::chrono::milliseconds(2200));
  const std::size_t sent_at_kill = progress.load();
  const int status = grab.signalAndWait(SIGKILL);
  tx.join();
  ASSERT_TRUE(WIFSIGNALED(status));
  const auto recorded = test::readRawlog(grab.out + "/grab_000.rawlog");
  // A prefix of what was sent, missing at most ~1 s (flush 0.5 s + reorder 0.3 s + one sweep).
  ASSERT_LE(recorded.size(), expected.size());
  for (std::size_t i = 0; i < recorded.size(); ++i) ASSERT_TRUE(recorded[i] == expected[i]) << "packet " << i;
  EXPECT_GE(recorded.size() + 754, sent_at_kill) << recorded.size() << " recorded, " << sent_at_kill << " sent";
  EXPECT_GT(recorded.size(), 0u);
  // The pcap sidecar (flushed with the rawlog, written before the reorder window) likewise.
  std::string pcap_error;
  const auto sidecar = pcap::readUdpDatagrams(grab.out + "/lidar_000.pcap", 2368, &pcap_error);
  ASSERT_LE(sidecar.size(), expected.size());
  for (std::size_t i = 0; i < sidecar.size(); ++i) ASSERT_TRUE(sidecar[i].payload == expected[i]) << "pcap packet " << i;
  EXPECT_GE(sidecar.size(), recorded.size());
  RecordProperty("pcap_packets_readable", int(sidecar.size()));
  RecordProperty("packets_sent_at_kill", int(sent_at_kill));
  RecordProperty("packets_readable", int(recorded.size()));
  // The summary refreshed while recording is there and parses (written atomically).
  const auto summary = nlohmann::json::parse(test::readAll(grab.out + "/summary.json"));
  EXPECT_GT(summary["packets_received"].get<std::size_t>(), 0u);
}

// Configuration errors end the app at once with exit code 1 and a line naming the file and key.
TEST(GrabApp, BadIniExitsWithTheKeyNamed) {
  const std::string exe = std::string(ROADSLAM_BINARY_DIR) + "/bin/roadslam-grab";
  if (!std::filesystem::exists(exe)) GTEST_SKIP() << "bin/roadslam-grab not built";
  test::TempDir dir("badini");
  const std::string ini = dir.str() + "/bad.ini";
  std::ofstream(ini) << "[grab]\nsensors = lidar\n[lidar]\ndata_port = 0\nposition_port = 0\nyaw_degs = 3\n";
  const std::string cmd = exe + " --config " + ini + " --out " + dir.str() + "/s --duration 1 2> " + dir.str() + "/err";
  const int rc = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(rc), 1);
  const std::string err = test::readAll(dir.str() + "/err");
  EXPECT_NE(err.find("bad.ini"), std::string::npos) << err;
  EXPECT_NE(err.find("yaw_degs"), std::string::npos) << err;
}
