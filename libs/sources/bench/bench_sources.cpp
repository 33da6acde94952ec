// Throughput of the packet sources, and live UDP loss of our receiver against MRPT's
// CVelodyneScanner at the same send rates (MRPT-NOTES.md: it received 465 of 750 packets at
// 1,508 packets/s). Compare the two as ratios from one run; machines are noisy.
#include <arpa/inet.h>
#include <benchmark/benchmark.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <mrpt/hwdrivers/CVelodyneScanner.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include "roadslam/sources/boxroom.h"
#include "roadslam/sources/pcap_source.h"
#include "roadslam/sources/rawlog_source.h"
#include "roadslam/sources/recording.h"
#include "roadslam/sources/sweep_source.h"
#include "roadslam/sources/udp_receiver.h"

using namespace roadslam::sources;
namespace velodyne = roadslam::velodyne;
namespace fs = std::filesystem;

namespace {

const std::string kVlp16 =
    std::string(ROADSLAM_SHARED_DATA) + "/velodyne/veloview_vlp-16-test-90deg-1-50-frames.pcap";

const std::string& rawlogCopy() {
  static const std::string path = [] {
    const std::string p = (fs::temp_directory_path() / "bench_sources_vlp16.rawlog").string();
    velodyne::DecoderParams dp;
    dp.model = velodyne::Model::VLP16;
    convertToRawlog(kVlp16, p, dp);
    return p;
  }();
  return path;
}

template <class Source>
void replay(benchmark::State& state, const std::string& path) {
  if (!fs::exists(path)) return state.SkipWithError(("missing " + path).c_str());
  uint64_t packets = 0;
  for (auto _ : state) {
    Source src(path);
    while (auto p = src.next()) benchmark::DoNotOptimize(p->payload.data());
    packets += src.stats().data_packets;
  }
  state.counters["packets/s"] = benchmark::Counter(double(packets), benchmark::Counter::kIsRate);
}

void BM_PcapReplay(benchmark::State& s) { replay<PcapPacketSource>(s, kVlp16); }
void BM_RawlogReplay(benchmark::State& s) {
  if (!fs::exists(kVlp16)) return s.SkipWithError(("missing " + kVlp16).c_str());
  replay<RawlogPacketSource>(s, rawlogCopy());
}

void BM_PcapSweeps(benchmark::State& state) {
  if (!fs::exists(kVlp16)) return state.SkipWithError(("missing " + kVlp16).c_str());
  velodyne::DecoderParams dp;
  dp.model = velodyne::Model::VLP16;
  uint64_t points = 0;
  for (auto _ : state) {
    SweepSource src(std::make_unique<PcapPacketSource>(kVlp16), dp);
    while (auto s = src.next()) points += s->points.size();
  }
  state.counters["points/s"] = benchmark::Counter(double(points), benchmark::Counter::kIsRate);
}

// Sends \p n real box-room data packets to 127.0.0.1:port at \p rate packets/s.
void sendPaced(uint16_t port, int n, double rate, std::atomic<bool>& done) {
  static const auto packets = [] {
    const std::string p = (fs::temp_directory_path() / "bench_sources_box.pcap").string();
    writeBoxRoomPcap(p);
    std::vector<std::vector<uint8_t>> v;
    PcapPacketSource src(p);
    while (auto pkt = src.next())
      if (pkt->dst_port == 2368) v.push_back(pkt->payload);
    return v;
  }();
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < n; ++i) {
    std::this_thread::sleep_until(t0 + std::chrono::duration<double>(i / rate));
    const auto& p = packets[std::size_t(i) % packets.size()];
    sendto(fd, p.data(), p.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  }
  close(fd);
  done = true;
}

constexpr int kLivePackets = 1500;

void BM_LiveUdpReceiver(benchmark::State& state) {
  const double rate = double(state.range(0));
  double received = 0;
  for (auto _ : state) {
    UdpReceiver::Params p;
    p.ports = {0, 0};
    p.bind_address = "127.0.0.1";
    p.poll_timeout_s = 0.2;
    UdpReceiver rx(p);
    std::atomic<bool> done{false};
    std::thread tx(sendPaced, rx.dataPort(), kLivePackets, rate, std::ref(done));
    int got = 0;
    while (rx.next() || !done) ++got;
    while (rx.next()) ++got;
    tx.join();
    received = rx.stats().data_packets;
  }
  state.counters["received_fraction"] = received / kLivePackets;
}

void BM_LiveMrptCVelodyneScanner(benchmark::State& state) {
  const double rate = double(state.range(0));
  double received = 0;
  for (auto _ : state) {
    mrpt::hwdrivers::CVelodyneScanner mrpt_rx;
    mrpt_rx.setModelName(mrpt::hwdrivers::CVelodyneScanner::VLP16);
    try {
      mrpt_rx.initialize();  // binds the fixed ports 2368 / 8308
    } catch (const std::exception& e) {
      return state.SkipWithError(e.what());
    }
    std::atomic<bool> done{false};
    std::thread tx(sendPaced, uint16_t(2368), kLivePackets, rate, std::ref(done));
    mrpt::obs::CObservationVelodyneScan::TVelodyneRawPacket data;
    mrpt::obs::CObservationVelodyneScan::TVelodynePositionPacket pos;
    int got = 0, idle = 0;
    while (!done || idle < 200) {
      mrpt::system::TTimeStamp td, tp;
      mrpt_rx.receivePackets(td, data, tp, pos);
      if (td != INVALID_TIMESTAMP) {
        ++got;
        idle = 0;
      } else if (done) {
        ++idle;
      }
    }
    tx.join();
    received = got;
  }
  state.counters["received_fraction"] = received / kLivePackets;
}

}  // namespace

BENCHMARK(BM_PcapReplay)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RawlogReplay)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PcapSweeps)->Unit(benchmark::kMillisecond);
// Send rates: one VLP-16 (754/s), twice that (the MRPT-NOTES test), and ten times.
BENCHMARK(BM_LiveUdpReceiver)->Arg(754)->Arg(1508)->Arg(7540)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LiveMrptCVelodyneScanner)->Arg(754)->Arg(1508)->Arg(7540)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
