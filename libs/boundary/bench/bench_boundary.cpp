// Time per sweep of the boundary detector on a VLP-16-like sweep (28.8k rays, 10 Hz, 0.2 deg) of a
// street with curbs and parked cars; the thesis baseline and the ground labelling alone in the same
// run for ratios. Target: <= 20 ms per sweep on one core.
#include <benchmark/benchmark.h>

#include "../tests/synthetic_road.h"
#include "roadslam/boundary/detector.h"
#include "roadslam/preprocess/ground_segmentation.h"

using namespace roadslam;

namespace {

const Scan& street() {
  static const Scan s = [] {
    boundary::test::Road r;
    for (double x = -30; x < 40; x += 9.0) r.boxes.push_back({x, x + 4.5, -3.3, -1.5, -1.9, -0.4});
    r.boxes.push_back({15, 19.5, 0.5, 2.3, -1.9, -0.4});                 // oncoming car
    for (double x = -40; x < 60; x += 15) r.boxes.push_back({x, x + 10, 7, 12, -1.9, 10});  // buildings
    return boundary::test::castSweep(r);
  }();
  return s;
}

/// The rules of ini/bounds-parking.ini against parked cars read as curbs.
void parkingRules(boundary::Params& p) {
  p.curb_min_range_m = 5, p.curb_level_cells = 5, p.curb_veto_cells = 2;
}

void run(benchmark::State& st, boundary::Method method, bool parallel = true, double yaw_per_sweep = 0.0,
         bool bend = true, bool parking = false, int draws = 0) {
  boundary::Params p;
  p.method = method;
  if (draws > 0) p.ransac_iterations = draws;  // e.g. 200: a faster, less robust fit
  if (parking) parkingRules(p);
  if (!parallel) p.parallel_max_spread_m = 0;  // before: no side continued parallel to the other
  if (!bend) p.bend_max_curvature = 0;         // before: fits in the driven path's arc only, no bend searched
  boundary::BoundaryDetector det(p);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (auto _ : st) {
    T.translation() += T.linear().col(0);  // memory and map-frame bookkeeping as while driving (1 m per sweep)
    T.rotate(Eigen::AngleAxisd(yaw_per_sweep, Eigen::Vector3d::UnitZ()));  // turning: fits in the arc frame
    benchmark::DoNotOptimize(det.process(street(), T, 0.0));
  }
  st.counters["points"] = static_cast<double>(street().points.size());
}

void BM_Detector_Ransac(benchmark::State& st) { run(st, boundary::Method::Ransac); }
void BM_Detector_Ransac_200Draws(benchmark::State& st) { run(st, boundary::Method::Ransac, true, 0.0, true, false, 200); }
void BM_Detector_Ransac_NoParallel(benchmark::State& st) { run(st, boundary::Method::Ransac, false); }
void BM_Detector_Ransac_NoBend(benchmark::State& st) { run(st, boundary::Method::Ransac, true, 0.0, false); }
void BM_Detector_Ransac_Turning(benchmark::State& st) { run(st, boundary::Method::Ransac, true, 1.0 / 14.0); }  // R = 14 m
void BM_Detector_Ransac_Turning_NoBend(benchmark::State& st) { run(st, boundary::Method::Ransac, true, 1.0 / 14.0, false); }
void BM_Detector_Ransac_ParkingRules(benchmark::State& st) { run(st, boundary::Method::Ransac, true, 0.0, true, true); }
void BM_Detector_Thesis(benchmark::State& st) { run(st, boundary::Method::Thesis); }
/// Whole-drive mode: a 300 m drive (1 m per sweep) accumulated, then sweeps of its middle fitted
/// from the whole drive's curb map along its path (pass 2); pass 1 (labelling, map) on its own.
Eigen::Isometry3d along(int i) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().x() = i;
  return T;
}
void BM_Detector_WholeDrive(benchmark::State& st) {
  boundary::BoundaryDetector det{boundary::Params{}};
  for (int i = 0; i < 300; ++i) det.accumulate(street(), along(i), 0.1 * i);
  det.finishAccumulation();
  int i = 50;
  for (auto _ : st) {
    benchmark::DoNotOptimize(det.process(street(), along(i), 0.1 * i));
    i = i < 250 ? i + 1 : 50;
  }
  st.counters["cells"] = static_cast<double>(det.curbMap().size());
}
void BM_Detector_WholeDrive_FirstPass(benchmark::State& st) {
  boundary::BoundaryDetector det{boundary::Params{}};
  int i = 0;
  for (auto _ : st) det.accumulate(street(), along(i), 0.1 * i), ++i;
}
void BM_GroundLabelsOnly(benchmark::State& st) {
  preprocess::GroundSegParams g;
  for (auto _ : st) benchmark::DoNotOptimize(preprocess::segmentGroundWithHeights(street().points, g));
}
void BM_LabelPoints(benchmark::State& st) {
  boundary::Params p;
  for (auto _ : st) benchmark::DoNotOptimize(boundary::labelPoints(street(), p));
}
void BM_LabelPoints_ParkingRules(benchmark::State& st) {
  boundary::Params p;
  parkingRules(p);
  for (auto _ : st) benchmark::DoNotOptimize(boundary::labelPoints(street(), p));
}

}  // namespace

BENCHMARK(BM_Detector_Ransac)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Detector_Ransac_200Draws)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Detector_Ransac_NoParallel)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Detector_Ransac_NoBend)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Detector_Ransac_Turning)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Detector_Ransac_Turning_NoBend)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Detector_Ransac_ParkingRules)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Detector_Thesis)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Detector_WholeDrive)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Detector_WholeDrive_FirstPass)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GroundLabelsOnly)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LabelPoints)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LabelPoints_ParkingRules)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
