// Decoding speed on the real RAV4 minute (135,468 frames, both buses), one core:
//  - BM_DecodeVehicleSignals: the RAV4 vehicle signal set (ini/vehicles/toyota-rav4-2017.ini: 4 wheel
//    speeds, speed, yaw rate, steering angle + fraction, accelerations, gear) with can::Decoder;
//  - BM_DecodeAllSignals: every signal of every message in the DBC;
//  - BM_CanmatrixPython: the same frames and signal set through python3-canmatrix
//    (libs/can/bench/canmatrix_bench.py), run once; the counter "cpp_over_python" is the ratio.
#include <roadslam/can/candump.h>
#include <roadslam/can/decoder.h>

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>

using namespace roadslam::can;

namespace {
const std::string kDir = std::string(ROADSLAM_SHARED_DATA) + "/can/rav4-2017/";
const std::string kLog = kDir + "rav4_2018-08-02_seg40.candump.log";
const std::string kDbc = kDir + "toyota_new_mc_pt_generated.dbc";
const std::vector<std::string> kVehicleSignals = {
    "WHEEL_SPEEDS.WHEEL_SPEED_FL", "WHEEL_SPEEDS.WHEEL_SPEED_FR", "WHEEL_SPEEDS.WHEEL_SPEED_RL",
    "WHEEL_SPEEDS.WHEEL_SPEED_RR", "SPEED.SPEED", "KINEMATICS.YAW_RATE", "KINEMATICS.ACCEL_X",
    "KINEMATICS.ACCEL_Y", "STEER_ANGLE_SENSOR.STEER_ANGLE", "STEER_ANGLE_SENSOR.STEER_FRACTION",
    "GEAR_PACKET.GEAR"};

const std::vector<CanFrame>& frames() {
  static const std::vector<CanFrame> f = std::filesystem::exists(kLog) ? readCandumpFile(kLog) : std::vector<CanFrame>{};
  return f;
}

void run(benchmark::State& state, const Decoder& dec) {
  const auto& fr = frames();
  double out[64];
  double sink = 0;
  for (auto _ : state) {
    for (const CanFrame& f : fr) {
      if (dec.decode(f, out, nullptr) == DecodeStatus::kOk) sink += out[0];
    }
    benchmark::DoNotOptimize(sink);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * fr.size()));
}
}  // namespace

static void BM_DecodeVehicleSignals(benchmark::State& state) {
  if (frames().empty()) {
    state.SkipWithError(("missing " + kLog).c_str());
    return;
  }
  const Decoder dec(loadDbcFile(kDbc), kVehicleSignals);
  run(state, dec);
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(state.iterations() * frames().size()),
                                                      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_DecodeVehicleSignals)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

static void BM_DecodeAllSignals(benchmark::State& state) {
  if (frames().empty()) {
    state.SkipWithError(("missing " + kLog).c_str());
    return;
  }
  const Decoder dec(loadDbcFile(kDbc));
  run(state, dec);
}
BENCHMARK(BM_DecodeAllSignals)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();

// Runs the python peer once (its own timing of the decode loop is read from its output) and times
// the C++ decoder on the same frames in the same run, reporting both rates and their ratio.
static void BM_CanmatrixPython(benchmark::State& state) {
  if (frames().empty()) {
    state.SkipWithError(("missing " + kLog).c_str());
    return;
  }
  const std::string script = std::string(ROADSLAM_SOURCE_DIR) + "/libs/can/bench/canmatrix_bench.py";
  std::string signals;
  for (const auto& s : kVehicleSignals) signals += (signals.empty() ? "" : ",") + s;
  double py = 0;
  for (auto _ : state) {
    const std::string cmd = "/usr/bin/python3 " + script + " " + kDbc + " " + kLog + " " + signals + " 2>/dev/null";
    std::unique_ptr<FILE, int (*)(FILE*)> p(popen(cmd.c_str(), "r"), pclose);
    if (!p || std::fscanf(p.get(), "%lf", &py) != 1) {
      state.SkipWithError("python3-canmatrix not available to /usr/bin/python3");
      return;
    }
  }
  const Decoder dec(loadDbcFile(kDbc), kVehicleSignals);
  double out[64], sink = 0;
  constexpr int kPasses = 20;
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < kPasses; ++i) {
    for (const CanFrame& f : frames()) {
      if (dec.decode(f, out, nullptr) == DecodeStatus::kOk) sink += out[0];
    }
  }
  benchmark::DoNotOptimize(sink);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpp = kPasses * static_cast<double>(frames().size()) / secs;
  state.counters["python_frames_per_s"] = py;
  state.counters["cpp_frames_per_s"] = cpp;
  state.counters["cpp_over_python"] = cpp / py;
}
BENCHMARK(BM_CanmatrixPython)->Iterations(1)->Unit(benchmark::kSecond);

BENCHMARK_MAIN();
