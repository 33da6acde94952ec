// Live capture to pcap: what the receiver got over loopback is recorded unchanged and replays
// through PcapPacketSource byte for byte.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "roadslam/common/stop_signal.h"
#include "roadslam/sources/boxroom.h"
#include "roadslam/sources/pcap_source.h"
#include "roadslam/sources/recorder.h"
#include "roadslam/sources/udp_receiver.h"

using namespace roadslam::sources;
namespace fs = std::filesystem;

namespace {
fs::path tmp(const std::string& name) {
  return fs::temp_directory_path() / (name + std::to_string(getpid()));
}
UdpReceiver::Params loopback() {
  UdpReceiver::Params p;
  p.ports = {0, 0};
  p.bind_address = "127.0.0.1";
  p.poll_timeout_s = 0.05;
  return p;
}
}  // namespace

TEST(Recorder, LiveLoopbackCaptureReplaysByteIdentical) {
  BoxRoomParams bp;
  bp.revolutions = 2;
  const fs::path box = tmp("rec_box_").string() + ".pcap";
  writeBoxRoomPcap(box.string(), bp);
  std::vector<roadslam::velodyne::RawPacket> sent;
  {
    PcapPacketSource src(box.string());
    while (auto p = src.next()) sent.push_back(*p);
  }
  UdpReceiver rx(loopback());
  std::thread sender([&] {
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    for (std::size_t i = 0; i < sent.size(); ++i) {
      to.sin_port = htons(sent[i].dst_port == 2368 ? rx.dataPort() : rx.positionPort());
      sendto(fd, sent[i].payload.data(), sent[i].payload.size(), 0,
             reinterpret_cast<sockaddr*>(&to), sizeof to);
      if (i % 10 == 0) std::this_thread::sleep_for(std::chrono::microseconds(300));
    }
    close(fd);
  });
  const fs::path out = tmp("rec_out_").string() + ".pcap";
  RecordLimits limits;
  limits.max_packets = sent.size();
  limits.duration_s = 10;  // bound in time should a datagram get lost
  const RecordSummary sum = recordToPcap(rx, out.string(), limits);
  sender.join();
  ASSERT_EQ(sum.packets, sent.size());
  EXPECT_EQ(sum.source.kernel_drops, 0u);

  // Replay: same payloads per port and in order, kernel stamps kept and monotonic.
  PcapPacketSource replay(out.string());  // recorded on the standard ports 2368 / 8308
  std::vector<std::vector<uint8_t>> want_data, want_pos, got_data, got_pos;
  for (const auto& p : sent) (p.dst_port == 2368 ? want_data : want_pos).push_back(p.payload);
  double last[2] = {0, 0};  // per port: the two sockets are separate kernel queues
  while (auto p = replay.next()) {
    double& l = last[p->dst_port == 2368 ? 0 : 1];
    EXPECT_GE(p->stamp_s, l);
    l = p->stamp_s;
    EXPECT_EQ(p->src_ip, 0x7F000001u);
    (p->dst_port == 2368 ? got_data : got_pos).push_back(p->payload);
  }
  EXPECT_EQ(got_data, want_data);
  EXPECT_EQ(got_pos, want_pos);
  EXPECT_EQ(replay.stats().missing_packets, 0u);
  fs::remove(box);
  fs::remove(out);
}

TEST(Recorder, NothingReceivedThrowsNamingTheOutputAndWritesNothing) {
  UdpReceiver rx(loopback());
  const fs::path out = tmp("rec_empty_").string() + ".pcap";
  RecordLimits limits;
  limits.duration_s = 0.15;
  try {
    recordToPcap(rx, out.string(), limits);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(out.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(out));
  for (const auto& entry : fs::directory_iterator(fs::temp_directory_path()))
    EXPECT_EQ(entry.path().string().find(out.string() + ".tmp"), std::string::npos);
}

// A stop request (what Ctrl-C turns into, roadslam/common/stop_signal.h) ends a live recording
// between packets and keeps a complete capture of what came before it.
TEST(Recorder, StopRequestEndsALiveRecordingWithACompleteCapture) {
  struct Endless : PacketSource {  // live: never finishes; asks to stop after 50 packets
    SourceStats st;
    std::optional<roadslam::velodyne::RawPacket> next() override {
      roadslam::velodyne::RawPacket p;
      p.stamp_s = 1000.0 + 1e-3 * double(st.packets);
      p.dst_port = 2368;
      p.payload.assign(roadslam::velodyne::kDataPacketSize, 0);
      ++st.packets;
      if (st.packets == 50) roadslam::requestStop();
      return p;
    }
    bool finished() const override { return false; }
    const SourceStats& stats() const override { return st; }
    std::string describe() const override { return "endless"; }
  } src;
  const fs::path out = tmp("rec_stop_").string() + ".pcap";
  roadslam::clearStopRequest();
  const RecordSummary sum = recordToPcap(src, out.string(), RecordLimits{});
  roadslam::clearStopRequest();
  EXPECT_EQ(sum.packets, 50u);
  PcapPacketSource replay(out.string());
  size_t n = 0;
  while (replay.next()) ++n;
  EXPECT_EQ(n, 50u);
  EXPECT_TRUE(replay.errorMessage().empty()) << replay.errorMessage();
  fs::remove(out);
}
