// Frame sources: the SocketCAN read loop over socketpair(AF_UNIX, SOCK_SEQPACKET) carrying the
// kernel's can_frame / canfd_frame; a real CAN socket where the kernel has vcan; log replay.
#include <roadslam/can/socketcan_source.h>

#include <linux/can.h>
#include <linux/can/error.h>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>

using namespace roadslam::can;

namespace {
void sendClassic(int fd, canid_t id, std::initializer_list<std::uint8_t> data) {
  can_frame k{};
  k.can_id = id;
  k.len = static_cast<std::uint8_t>(data.size());
  std::copy(data.begin(), data.end(), k.data);
  ASSERT_EQ(::send(fd, &k, sizeof(k), 0), static_cast<ssize_t>(CAN_MTU));
}
}  // namespace

TEST(SocketCanSource, ReadLoopOverSocketpair) {
  int sv[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv), 0) << std::strerror(errno);
  SocketCanSource src = SocketCanSource::fromFd(sv[0], "can7");
  sendClassic(sv[1], 0x123, {0xDE, 0xAD});
  sendClassic(sv[1], 0x12345678 | CAN_EFF_FLAG, {1, 2, 3, 4, 5, 6, 7, 8});
  sendClassic(sv[1], 0x321 | CAN_RTR_FLAG, {});
  sendClassic(sv[1], CAN_ERR_FLAG | CAN_ERR_BUSOFF, {0, 0, 0, 0, 0, 0, 0, 0});
  canfd_frame fd{};
  fd.can_id = 0x7FF;
  fd.len = 64;
  fd.flags = CANFD_BRS;
  for (int i = 0; i < 64; ++i) fd.data[i] = static_cast<std::uint8_t>(i);
  ASSERT_EQ(::send(sv[1], &fd, sizeof(fd), 0), static_cast<ssize_t>(CANFD_MTU));
  const char junk[5] = {1, 2, 3, 4, 5};
  ASSERT_EQ(::send(sv[1], junk, sizeof(junk), 0), 5);  // wrong size: counted, skipped
  sendClassic(sv[1], 0x001, {0x42});

  CanFrame f;
  const auto now_us = [] {
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
  };
  ASSERT_EQ(src.read(f, 1000), ReadStatus::kFrame);
  EXPECT_LE(f.t_us, now_us());  // kernel receive stamp (SO_TIMESTAMP works on AF_UNIX too)
  EXPECT_GT(f.t_us, now_us() - 10 * 1000000LL);
  EXPECT_EQ(f.id, 0x123U);
  EXPECT_EQ(f.len, 2);
  EXPECT_EQ(f.data[1], 0xAD);
  EXPECT_STREQ(f.iface.data(), "can7");
  ASSERT_EQ(src.read(f, 1000), ReadStatus::kFrame);
  EXPECT_TRUE(f.extended());
  EXPECT_EQ(f.id, 0x12345678U);
  EXPECT_EQ(f.data[7], 8);
  ASSERT_EQ(src.read(f, 1000), ReadStatus::kFrame);
  EXPECT_TRUE(f.remote());
  ASSERT_EQ(src.read(f, 1000), ReadStatus::kFrame);
  EXPECT_TRUE(f.error());
  EXPECT_EQ(f.id, static_cast<std::uint32_t>(CAN_ERR_BUSOFF));
  ASSERT_EQ(src.read(f, 1000), ReadStatus::kFrame);
  EXPECT_TRUE(f.fd());
  EXPECT_EQ(f.fd_flags, kFdBrs);
  EXPECT_EQ(f.len, 64);
  EXPECT_EQ(f.data[63], 63);
  EXPECT_EQ(src.read(f, 1000), ReadStatus::kTimeout);  // the junk datagram
  ASSERT_EQ(src.read(f, 1000), ReadStatus::kFrame);
  EXPECT_EQ(f.data[0], 0x42);
  EXPECT_EQ(src.read(f, 10), ReadStatus::kTimeout);  // nothing pending
  ::close(sv[1]);
  EXPECT_EQ(src.read(f, 1000), ReadStatus::kEnd);
  EXPECT_EQ(src.stats().frames, 6U);
  EXPECT_EQ(src.stats().error_frames, 1U);
  EXPECT_EQ(src.stats().malformed, 1U);
}

TEST(SocketCanSource, RealSocketWhereTheKernelHasCan) {
  const int probe = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (probe < 0) GTEST_SKIP() << "socket(PF_CAN) fails with errno " << errno << ": no CAN in this kernel";
  ::close(probe);
  SocketCanParams p;
  p.interface = "vcan0";
  p.filters = parseFilters("123:7FF");
  try {
    SocketCanSource src(p);
    CanFrame f;
    EXPECT_EQ(src.read(f, 10), ReadStatus::kTimeout);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << "vcan0 not available: " << e.what();
  }
}

TEST(SocketCanSource, OpenFailureNamesInterfaceAndFiltersParse) {
  SocketCanParams p;
  p.interface = "nosuchcan9";
  try {
    SocketCanSource src(p);
    FAIL() << "opened a missing interface";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nosuchcan9"), std::string::npos) << e.what();
  }
  const auto f = parseFilters("123:7FF,~12345678:1FFFFFFF");
  ASSERT_EQ(f.size(), 2U);
  EXPECT_FALSE(f[0].extended);
  EXPECT_TRUE(f[1].extended);
  EXPECT_TRUE(f[1].invert);
  EXPECT_EQ(f[1].mask, 0x1FFFFFFFU);
  EXPECT_THROW(parseFilters("12G:7FF"), std::invalid_argument);
  EXPECT_THROW(parseFilters("123"), std::invalid_argument);
}

TEST(LogReplaySource, ReplaysEveryGoodFrameAndCountsBadLines) {
  const std::string path = ::testing::TempDir() + "/roadslam_replay.log";
  {
    std::ofstream o(path);
    o << "(1.000000) can0 123#01\nbad line\n(1.010000) can0 124#02\n(1.020000) can0 20000004#0000000000000000\n";
  }
  for (const bool realtime : {false, true}) {
    LogReplaySource src(path, realtime, 100.0);
    CanFrame f;
    int n = 0;
    while (src.read(f, 1000) == ReadStatus::kFrame) ++n;
    EXPECT_EQ(n, 3);
    EXPECT_EQ(src.stats().malformed, 1U);
    EXPECT_EQ(src.stats().error_frames, 1U);
    EXPECT_EQ(src.logStats().issues.at(0).line, 2U);
  }
}
