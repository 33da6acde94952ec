// Loss of the whole recording chain (UdpReceiver -> sweep grouping -> bounded queue -> rawlog +
// pcap sidecar on disk) at multiples of the VLP-16 packet rate (754 packets/s), side by side with
// MRPT's CVelodyneScanner receiving the same packets at the same rates (it binds the fixed ports
// 2368/8308: skipped when they are taken). Compare as fractions from one run; machines are noisy.
#include <arpa/inet.h>
#include <benchmark/benchmark.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/hwdrivers/CVelodyneScanner.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <thread>

#include <mrpt/obs/CObservationVelodyneScan.h>

#include "roadslam/grabber/grabber.h"
#include "roadslam/grabber/segment_writer.h"
#include "roadslam/sim/simulator.h"

using namespace roadslam;
namespace fs = std::filesystem;

namespace {

constexpr double kVlp16Rate = 754.0;  // packets/s (VLP-16 manual, 1327.104 us per packet)

struct Sink : sim::PacketSink {
  std::vector<std::vector<uint8_t>> data;
  void packet(double, uint16_t port, const uint8_t* d, std::size_t n) override {
    if (port == 2368) data.emplace_back(d, d + n);
  }
};

/// 2 s of the simulated urban loop (1,508 real-format data packets), simulated once.
const std::vector<std::vector<uint8_t>>& packets() {
  static const auto v = [] {
    auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
    p.duration_s = 2.0;
    sim::Simulator s(p);
    Sink sink;
    s.run(sink);
    return sink.data;
  }();
  return v;
}

/// Packets sent per run: 2 s worth at the rate, at least the 1,508 simulated ones (cycled; the
/// repeated sensor timestamps make the gap counter meaningless, so loss = sent - written).
std::size_t packetsFor(double rate) { return std::max(packets().size(), std::size_t(2.0 * rate)); }

void sendPaced(uint16_t port, double rate) {
  const auto& pk = packets();
  const std::size_t n = packetsFor(rate);
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(port);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < n; ++i) {
    std::this_thread::sleep_until(t0 + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                           std::chrono::duration<double>(double(i) / rate)));
    const auto& p = pk[i % pk.size()];
    ::sendto(fd, p.data(), p.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  }
  ::close(fd);
}

bool defaultPortsFree() {
  for (uint16_t port : {uint16_t(2368), uint16_t(8308)}) {
    const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
    ::close(fd);
    if (!ok) return false;
  }
  return true;
}

void BM_Grabber(benchmark::State& state) {
  const double rate = kVlp16Rate * double(state.range(0));
  const std::string dir = (fs::temp_directory_path() / ("bench_grabber_" + std::to_string(::getpid()))).string();
  double written = 0, dropped = 0;
  for (auto _ : state) {
    mrpt::config::CConfigFileMemory cfg(std::string(
        "[grab]\nsensors = lidar\n[lidar]\ndata_port = 0\nposition_port = 0\nbind_address = 127.0.0.1\n"));
    grabber::GrabParams p;
    p.loadFromConfigFile(cfg);
    {
      grabber::Grabber g(p, dir);
      g.start();
      sendPaced(g.dataPort(0), rate);
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      g.stop();
      const auto st = g.status();
      written = double(st.writer.packets);
      dropped = double(st.sensors[0].kernel_drops + st.sensors[0].queue_drops);
    }
    fs::remove_all(dir);
  }
  state.counters["received_fraction"] = written / double(packetsFor(rate));
  state.counters["dropped"] = dropped;
  state.counters["packets/s"] = rate;
}

void BM_MrptCVelodyneScanner(benchmark::State& state) {
  const double rate = kVlp16Rate * double(state.range(0));
  if (!defaultPortsFree()) return state.SkipWithError("ports 2368/8308 are in use (CVelodyneScanner binds them)");
  double received = 0;
  for (auto _ : state) {
    mrpt::hwdrivers::CVelodyneScanner rx;
    rx.setModelName(mrpt::hwdrivers::CVelodyneScanner::VLP16);
    try {
      rx.initialize();
    } catch (const std::exception& e) {
      return state.SkipWithError(e.what());
    }
    std::atomic<bool> done{false};
    std::thread tx([&] {
      sendPaced(2368, rate);
      done = true;
    });
    mrpt::obs::CObservationVelodyneScan::TVelodyneRawPacket data;
    mrpt::obs::CObservationVelodyneScan::TVelodynePositionPacket pos;
    int got = 0, idle = 0;
    while (!done || idle < 200) {
      mrpt::system::TTimeStamp td, tp;
      rx.receivePackets(td, data, tp, pos);
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
  state.counters["received_fraction"] = received / double(packetsFor(rate));
  state.counters["packets/s"] = rate;
}

/// The writer's disk side alone: CObservationVelodyneScan sweeps (75 real packets each) into a
/// gzip segment at level state.range(0), Z_SYNC_FLUSH every 5 sweeps (0.5 s at 10 Hz).
/// sweeps/s over 10 = the multiple of one VLP-16 the disk side sustains.
void BM_SegmentWriter(benchmark::State& state) {
  const auto& pk = packets();
  mrpt::obs::CObservationVelodyneScan obs;
  obs.calibration = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration("VLP16");
  obs.scan_packets.resize(75);
  const std::string dir = (fs::temp_directory_path() / ("bench_segment_" + std::to_string(::getpid()))).string();
  fs::create_directories(dir);
  grabber::SegmentPolicy pol;
  pol.compression_level = int(state.range(0));
  std::size_t sweeps = 0, offset = 0;
  {
    grabber::SegmentWriter w(dir, "b", pol);
    for (auto _ : state) {
      for (auto& p : obs.scan_packets) std::memcpy(&p, pk[offset++ % pk.size()].data(), sizeof(p));
      w.write(obs, 0);
      if (++sweeps % 5 == 0) w.syncFlush();
    }
    w.close();
    state.counters["compression_ratio"] = double(w.bytesUncompressed()) / double(w.totalBytes());
  }
  fs::remove_all(dir);
  state.counters["sweeps/s"] = benchmark::Counter(double(sweeps), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_SegmentWriter)->Arg(0)->Arg(1)->Arg(6)->UseRealTime()->Unit(benchmark::kMillisecond);
// Multiples of the VLP-16 rate: 1x, 2x, 5x, 10x, 20x, 50x, 100x.
BENCHMARK(BM_Grabber)->Arg(1)->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Arg(50)->Arg(100)->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MrptCVelodyneScanner)->Arg(1)->Arg(2)->Arg(5)->Arg(10)->Arg(20)->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
