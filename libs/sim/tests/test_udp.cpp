// UDP streaming to a loopback socket: every data packet arrives, in order, with the pcap's bytes.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <arpa/inet.h>
#include <atomic>
#include <thread>

#include "roadslam/pcap/pcap_reader.h"
#include "roadslam/sim/outputs.h"
#include "sim_test_util.h"

using namespace roadslam;
using namespace roadslam::sim;

TEST(SimUdp, LoopbackReceiverGetsEveryPacket) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  int rcvbuf = 8 << 20;
  ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof(rcvbuf));
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;  // a free port chosen by the kernel
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)), 0);
  socklen_t len = sizeof(a);
  ASSERT_EQ(::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len), 0);

  std::vector<std::vector<uint8_t>> received;
  std::atomic<bool> stop{false};
  std::thread rx([&] {
    std::vector<uint8_t> buf(2048);
    pollfd pfd{fd, POLLIN, 0};
    while (!stop || ::poll(&pfd, 1, 0) > 0) {  // drain what is queued after the sender is done
      if (::poll(&pfd, 1, 50) <= 0) continue;
      const ssize_t n = ::recv(fd, buf.data(), buf.size(), 0);
      if (n > 0) received.emplace_back(buf.begin(), buf.begin() + n);
    }
  });
  test::TempDir dir("udp");
  ScenarioParams p = ScenarioParams::fromFile(test::iniPath("urban-loop.ini"));
  p.duration_s = 0.4;  // 301 packets over 0.4 s: the receiver never falls 200 KB (rmem default) behind
  Simulator sim(p);
  OutputOptions opt;
  opt.dir = dir.str();
  opt.udp_host = "127.0.0.1";
  opt.udp_port = ntohs(a.sin_port);
  opt.udp_speed = 1.0;
  const RunReport rep = runToDirectory(sim, opt);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  stop = true;
  rx.join();
  ::close(fd);

  EXPECT_EQ(rep.packets_sent, rep.stats.data_packets);
  ASSERT_EQ(received.size(), rep.packets_sent);
  pcap::PcapReader reader(dir.str() + "/velodyne.pcap");
  pcap::UdpDatagram d;
  std::size_t i = 0;
  while (reader.next(d) == pcap::ReadStatus::Ok)
    if (d.dst_port == 2368) {
      ASSERT_LT(i, received.size());
      ASSERT_EQ(received[i++], d.payload) << "packet " << i;
    }
  EXPECT_EQ(i, received.size());
}
