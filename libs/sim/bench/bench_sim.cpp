// Simulator speed: packets (ray casting + encoding) per second on one core, as a real-time factor
// (simulated seconds per wall-clock second; >= 5 required). Run: build/bench/sim_bench
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "roadslam/sim/simulator.h"
#include "roadslam/velodyne/encoder.h"

using namespace roadslam::sim;

namespace {
const Simulator& scenario(const std::string& name) {
  static std::map<std::string, std::unique_ptr<Simulator>> cache;
  auto& s = cache[name];
  if (!s) s = std::make_unique<Simulator>(ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/" + name + ".ini"));
  return *s;
}

// One simulated second (754 packets) per iteration, starting 20 s into the drive (moving).
void BM_SimulateOneSecond(benchmark::State& state, const std::string& name) {
  const Simulator& sim = scenario(name);
  LidarSimulator lidar(sim.world(), sim.trajectory(), sim.params().lidar, sim.params().seed);
  std::array<roadslam::velodyne::FiringSequence, roadslam::velodyne::kVlp16SequencesPerPacket> seq{};
  const double P = LidarSimulator::packetPeriod_s();
  uint64_t k = static_cast<uint64_t>(20.0 / P);
  const uint64_t per_second = static_cast<uint64_t>(1.0 / P);
  for (auto _ : state) {
    for (uint64_t i = 0; i < per_second; ++i, ++k) {
      lidar.simulatePacket(k, seq, nullptr);
      auto bytes = roadslam::velodyne::encodeVlp16Packet(seq, static_cast<uint32_t>(k));
      benchmark::DoNotOptimize(bytes);
    }
  }
  const auto& c = lidar.counters();
  state.counters["real_time_factor"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(c.rays), benchmark::Counter::kIsRate);
  state.counters["return_ratio"] = static_cast<double>(c.returns) / static_cast<double>(std::max<uint64_t>(1, c.rays));
}
}  // namespace

BENCHMARK_CAPTURE(BM_SimulateOneSecond, urban_loop, std::string("urban-loop"))->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateOneSecond, highway, std::string("highway"))->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_CAPTURE(BM_SimulateOneSecond, tunnel, std::string("tunnel"))->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK_MAIN();
