// Odometry time per VLP-16 frame on one core, over simulated urban sweeps (decoded by our decoder),
// for the default pipeline (Gaussian voxel map) and for the registration library's methods against
// a local map of points (the target rebuilt whenever the map changes). Errors of the same drives are
// printed by build/bench/odometry_sim_table.
#include <benchmark/benchmark.h>

#include <ctime>

#include "roadslam/common/config.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/sim/sweep_sink.h"

using namespace roadslam;

namespace {

struct Drive {
  std::vector<Scan> sweeps;
};

const Drive& urbanDrive() {
  static Drive d = [] {
    auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
    p.duration_s = 12.0;
    p.trajectory.start_standing_s = 0;
    sim::Simulator s(p);
    Drive out;
    sim::SweepSink sink([&](Scan&& sc) {
      if (!sc.partial) out.sweeps.push_back(std::move(sc));
    });
    s.run(sink);
    return out;
  }();
  return d;
}

void runOdometry(benchmark::State& state, const odometry::Params& params) {
  const Drive& d = urbanDrive();
  size_t frames = 0;
  double cpu_s = 0;
  for (auto _ : state) {
    const std::clock_t c0 = std::clock();
    odometry::Odometry odo(params);
    for (const auto& s : d.sweeps) benchmark::DoNotOptimize(odo.process(s));
    cpu_s += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    frames += d.sweeps.size();
  }
  state.counters["cpu_ms_per_frame"] = 1e3 * cpu_s / static_cast<double>(frames);
  state.counters["frames"] = static_cast<double>(d.sweeps.size());
  state.counters["points_per_sweep"] = static_cast<double>(d.sweeps.front().points.size());
}

odometry::Params fromIni(const std::string& rel) {
  odometry::Params p;
  p.loadFromConfigFile(*loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/" + rel));
  return p;
}

void BM_Default(benchmark::State& s) { runOdometry(s, fromIni("ini/default.ini")); }
// The map before single rings off the road constrained (registration/src/gaussian_voxel_map.cpp): their cost.
void BM_DefaultWithoutRingLines(benchmark::State& s) {
  auto p = fromIni("ini/default.ini");
  p.map_ring_lines_on_walls = false;
  runOdometry(s, p);
}
void BM_RegistrationIcpPointToPlane(benchmark::State& s) {
  auto p = fromIni("ini/default.ini");
  p.matcher = roadslam::odometry::Matcher::Registration;
  p.registration.method = registration::Method::IcpPointToPlane;
  runOdometry(s, p);
}
void BM_RegistrationNdt(benchmark::State& s) {
  auto p = fromIni("ini/default.ini");
  p.matcher = roadslam::odometry::Matcher::Registration;
  p.registration.method = registration::Method::Ndt;
  runOdometry(s, p);
}

}  // namespace

BENCHMARK(BM_Default)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(2);
BENCHMARK(BM_DefaultWithoutRingLines)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(2);
BENCHMARK(BM_RegistrationIcpPointToPlane)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(1);
BENCHMARK(BM_RegistrationNdt)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(1);
BENCHMARK_MAIN();
