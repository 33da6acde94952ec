// Per-filter cost on one sweep: arg 0 = synthetic VLP-16 street sweep (~28k points), arg 1 = KITTI
// 00 scan 0 (HDL-64E, 124,668 points). Filters work in place, so every iteration copies the input;
// BM_Copy measures that copy alone and is the baseline to subtract. The odometry budget is 10 ms
// per VLP-16 frame on one core; preprocessing should take 1-2 ms of it.

#include "../tests/synthetic_scene.h"
#include "roadslam/common/config.h"
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/preprocess/chain.h"

#include <benchmark/benchmark.h>

#include <filesystem>

using namespace roadslam;
using namespace roadslam::preprocess;

namespace {
const std::vector<ScanPoint>* sweep(benchmark::State& st) {
  static const std::vector<ScanPoint> vlp16 = fixtures::makeStreetSweep(fixtures::StreetScene{}).scan.points;
  static const std::vector<ScanPoint> kitti = [] {
    const std::string path = std::string(ROADSLAM_SHARED_DATA) + "/kitti/odometry-00-first16/velodyne/000000.bin";
    return std::filesystem::exists(path) ? datasets::readKittiBin(path).points : std::vector<ScanPoint>{};
  }();
  const auto* pts = st.range(0) == 0 ? &vlp16 : &kitti;
  if (pts->empty()) {
    st.SkipWithError("KITTI sweep missing under ROADSLAM_SHARED_DATA");
    return nullptr;
  }
  st.SetLabel(st.range(0) == 0 ? "vlp16-synthetic" : "kitti-hdl64");
  return pts;
}

template <class F>
void run(benchmark::State& st, F filter) {
  const auto* in = sweep(st);
  if (!in) return;
  size_t out = 0;
  for (auto _ : st) {
    std::vector<ScanPoint> pts = *in;
    filter(pts);
    out = pts.size();
    benchmark::DoNotOptimize(pts.data());
  }
  st.counters["points_in"] = static_cast<double>(in->size());
  st.counters["points_out"] = static_cast<double>(out);
  st.SetItemsProcessed(static_cast<int64_t>(st.iterations() * in->size()));
}

PreprocessParams preset(const std::string& name) {
  PreprocessParams p;
  p.loadFromConfigFile(*loadIniFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + name), "preprocess");
  return p;
}
}  // namespace

static void BM_Copy(benchmark::State& st) { run(st, [](std::vector<ScanPoint>&) {}); }
static void BM_NonFinite(benchmark::State& st) { run(st, [](auto& p) { removeNonFinite(p); }); }
static void BM_Ego(benchmark::State& st) { run(st, [](auto& p) { removeEgo(p, EgoParams{}); }); }
static void BM_Range(benchmark::State& st) { run(st, [](auto& p) { removeOutOfRange(p, RangeParams{}); }); }
static void BM_Roi(benchmark::State& st) { run(st, [](auto& p) { removeOutsideRoi(p, RoiParams{}); }); }
static void BM_GroundRansac(benchmark::State& st) { run(st, [](auto& p) { removeGroundRansac(p, RansacGroundParams{}); }); }
static void BM_GroundLinefit(benchmark::State& st) {
  GroundSegParams g;
  g.sensor_height_m = st.range(0) == 0 ? 1.8 : 1.73;
  run(st, [&](auto& p) { removeGroundLinefit(p, g); });
}
static void BM_GroundLinefitParkedCarRules(benchmark::State& st) {
  GroundSegParams g;
  g.sensor_height_m = st.range(0) == 0 ? 1.8 : 1.73;
  g.parked_car_rules = g.level_start_behind_structure = true;
  run(st, [&](auto& p) { removeGroundLinefit(p, g); });
}
static void BM_RandomHalf(benchmark::State& st) { run(st, [](auto& p) { randomDownsample(p, RandomDownsampleParams{}); }); }
static void BM_VoxelCentroid(benchmark::State& st) {
  VoxelParams v;
  v.voxel_size_m = 0.01 * static_cast<double>(st.range(1));
  run(st, [&](auto& p) { voxelDownsample(p, v); });
}
static void BM_VoxelFirst(benchmark::State& st) {
  VoxelParams v;
  v.voxel_size_m = 0.01 * static_cast<double>(st.range(1));
  v.mode = VoxelParams::Mode::First;
  run(st, [&](auto& p) { voxelDownsample(p, v); });
}
static void BM_Sor(benchmark::State& st) { run(st, [](auto& p) { removeStatisticalOutliers(p, SorParams{}); }); }
static void BM_ChainPreset(benchmark::State& st) {
  const PreprocessParams p = preset(st.range(1) == 0 ? "preprocess-kitti.ini" : "preprocess-vlp16-ground-removal.ini");
  run(st, [&](auto& pts) {
    PreprocessChain chain(p);
    Scan s;
    s.points.swap(pts);
    chain.process(s);
    pts.swap(s.points);
  });
}

#define BOTH_SWEEPS Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)
BENCHMARK(BM_Copy)->BOTH_SWEEPS;
BENCHMARK(BM_NonFinite)->BOTH_SWEEPS;
BENCHMARK(BM_Ego)->BOTH_SWEEPS;
BENCHMARK(BM_Range)->BOTH_SWEEPS;
BENCHMARK(BM_Roi)->BOTH_SWEEPS;
BENCHMARK(BM_GroundRansac)->BOTH_SWEEPS;
BENCHMARK(BM_GroundLinefit)->BOTH_SWEEPS;
BENCHMARK(BM_GroundLinefitParkedCarRules)->BOTH_SWEEPS;
BENCHMARK(BM_RandomHalf)->BOTH_SWEEPS;
BENCHMARK(BM_VoxelCentroid)->ArgsProduct({{0, 1}, {20, 50}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_VoxelFirst)->ArgsProduct({{0, 1}, {20, 50}})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Sor)->BOTH_SWEEPS;
// second arg: 0 = preprocess-kitti.ini (ego,range,voxel 0.5), 1 = preprocess-vlp16-ground-removal.ini
BENCHMARK(BM_ChainPreset)->ArgsProduct({{0, 1}, {0, 1}})->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
