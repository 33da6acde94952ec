// Sends real-format packets over loopback from a thread and checks every one arrives intact.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <chrono>
#include <thread>

#include "roadslam/sources/udp_receiver.h"
#include "test_packets.h"

using namespace roadslam::sources;
using namespace roadslam::sources::test_support;

namespace {

void sendTo(int fd, uint16_t port, const std::vector<uint8_t>& payload) {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  sendto(fd, payload.data(), payload.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
}

UdpReceiver::Params loopbackParams() {
  UdpReceiver::Params p;
  p.ports = {0, 0};  // random free ports: tests never collide with a real sensor or each other
  p.bind_address = "127.0.0.1";
  p.poll_timeout_s = 0.05;
  return p;
}

}  // namespace

TEST(UdpReceiver, EveryPacketArrivesIntactWithMonotonicKernelStamps) {
  UdpReceiver rx(loopbackParams());
  ASSERT_NE(rx.dataPort(), 0);
  ASSERT_NE(rx.positionPort(), 0);
  EXPECT_GT(rx.grantedRcvbufBytes(), 0);

  constexpr int kData = 300, kPos = 20, kBad = 7;
  std::vector<std::vector<uint8_t>> data, pos;
  for (int k = 0; k < kData; ++k)
    data.push_back(makeDataPacket(uint32_t(k * 1327104LL / 1000), uint16_t(k * 480), 42 + k));
  for (int k = 0; k < kPos; ++k) pos.push_back(makePositionPacket(uint32_t(k * 20000), kAlmeriaRmc));

  std::thread sender([&] {
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    for (int k = 0; k < kData; ++k) {
      sendTo(fd, rx.dataPort(), data[k]);
      if (k % 15 == 0) sendTo(fd, rx.positionPort(), pos[k / 15]);
      if (k % 40 == 0 && k / 40 < kBad) sendTo(fd, rx.dataPort(), std::vector<uint8_t>(1000, 1));
      // Pace like a sensor (bounded: 300 packets in ~0.1 s) so loopback never overruns the buffer.
      if (k % 10 == 0) std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    close(fd);
  });

  std::vector<roadslam::velodyne::RawPacket> got_data, got_pos;
  int idle = 0;
  while (got_data.size() + got_pos.size() < std::size_t(kData + kPos) && idle < 40) {
    auto p = rx.next();
    if (!p) {
      ++idle;  // at most 40 x 50 ms of silence: the test is bounded in time
      continue;
    }
    idle = 0;
    (p->dst_port == rx.dataPort() ? got_data : got_pos).push_back(std::move(*p));
  }
  sender.join();

  ASSERT_EQ(got_data.size(), std::size_t(kData));
  ASSERT_EQ(got_pos.size(), std::size_t(kPos));
  for (int k = 0; k < kData; ++k) {
    EXPECT_EQ(got_data[k].payload, data[k]) << "data packet " << k;
    EXPECT_EQ(got_data[k].src_ip, 0x7F000001u);
    if (k > 0) {
      EXPECT_GE(got_data[k].stamp_s, got_data[k - 1].stamp_s);
    }
  }
  for (int k = 0; k < kPos; ++k) EXPECT_EQ(got_pos[k].payload, pos[k]) << "position packet " << k;
  const double now = std::chrono::duration<double>(
                         std::chrono::system_clock::now().time_since_epoch()).count();
  EXPECT_NEAR(got_data.front().stamp_s, now, 60.0) << "kernel stamps are wall-clock seconds";
  EXPECT_EQ(rx.stats().malformed_packets, std::size_t(kBad));
  EXPECT_EQ(rx.stats().missing_packets, 0u);
  EXPECT_EQ(rx.stats().kernel_drops, 0u);
  EXPECT_EQ(rx.stats().data_packets, std::size_t(kData));
}

TEST(UdpReceiver, KernelOverflowIsCountedExactly) {
  // A tiny socket buffer and nobody reading: most datagrams are dropped by the kernel. Every one
  // sent is then either received or counted by SO_RXQ_OVFL (the counter value rides on the next
  // queued datagram, hence the final sentinel sent after draining).
  auto params = loopbackParams();
  params.rcvbuf_bytes = 1;  // the kernel rounds up to its minimum
  UdpReceiver rx(params);
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  constexpr int kBurst = 200;
  for (int k = 0; k < kBurst; ++k)
    sendTo(fd, rx.dataPort(), makeDataPacket(uint32_t(k * 1327104LL / 1000), 0, k));
  int got = 0, idle = 0;
  while (idle < 3) rx.next() ? ++got : ++idle;
  sendTo(fd, rx.dataPort(), makeDataPacket(uint32_t(kBurst * 1327104LL / 1000), 0, kBurst));
  idle = 0;
  while (idle < 3) rx.next() ? ++got : ++idle;
  close(fd);
  EXPECT_GT(rx.stats().kernel_drops, 0u);
  EXPECT_EQ(uint64_t(got) + rx.stats().kernel_drops, uint64_t(kBurst + 1));
  // The sensor clock shows the same loss.
  EXPECT_EQ(rx.stats().missing_packets, rx.stats().kernel_drops);
}

TEST(UdpReceiver, SourceFilterRejectsOtherSenders) {
  auto params = loopbackParams();
  params.source_filter = "192.168.1.201";  // the VLP-16 factory address; we send from 127.0.0.1
  UdpReceiver rx(params);
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  for (int k = 0; k < 5; ++k) sendTo(fd, rx.dataPort(), makeDataPacket(uint32_t(k * 1327), 0, k));
  close(fd);
  int idle = 0;
  while (rx.stats().skipped_packets < 5 && idle < 20) {
    EXPECT_FALSE(rx.next().has_value());
    ++idle;
  }
  EXPECT_EQ(rx.stats().skipped_packets, 5u);
  EXPECT_EQ(rx.stats().packets, 0u);
}

TEST(UdpReceiver, GapsInSensorCounterAreReportedAsMissing) {
  UdpReceiver rx(loopbackParams());
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  for (int k = 0; k < 30; ++k)
    if (k != 10 && k != 11) sendTo(fd, rx.dataPort(), makeDataPacket(uint32_t(k * 1327104LL / 1000), 0, k));
  close(fd);
  int idle = 0, got = 0;
  while (got < 28 && idle < 20) rx.next() ? ++got : ++idle;
  EXPECT_EQ(got, 28);
  EXPECT_EQ(rx.stats().missing_packets, 2u);
}

TEST(UdpReceiver, BadOrNonLocalBindAddressThrows) {
  auto params = loopbackParams();
  params.bind_address = "not-an-ip";
  EXPECT_THROW(UdpReceiver rx(params), std::runtime_error);
  params.bind_address = "203.0.113.7";  // TEST-NET-3: not a local address, bind() fails
  try {
    UdpReceiver rx(params);
    FAIL() << "bind to a non-local address succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bind"), std::string::npos) << e.what();
  }
}

TEST(UdpReceiver, ParamsRoundTripThroughIni) {
  UdpReceiver::Params p;
  p.ports = {2400, 8400, roadslam::velodyne::Model::HDL32};
  p.source_filter = "10.0.0.5";
  p.poll_timeout_s = 0.25;
  p.packet_period_s = 663.552e-6;
  mrpt::config::CConfigFileMemory ini;
  p.saveToConfigFile(ini, "udp");
  UdpReceiver::Params q;
  q.loadFromConfigFile(ini, "udp");
  EXPECT_EQ(q.ports.data_port, 2400);
  EXPECT_EQ(q.ports.position_port, 8400);
  EXPECT_EQ(q.ports.model, roadslam::velodyne::Model::HDL32);
  ini.write("udp", "model", std::string("hdl64"));
  EXPECT_THROW(q.loadFromConfigFile(ini, "udp"), std::runtime_error);
  EXPECT_EQ(q.source_filter, "10.0.0.5");
  EXPECT_NEAR(q.poll_timeout_s, 0.25, 1e-12);
  EXPECT_NEAR(q.packet_period_s, 663.552e-6, 1e-12);
}
