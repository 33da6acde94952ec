// Clustering + tracking per sweep on a ray-cast VLP-16 street (8 cars/poles, ~20k points): the
// issue's budget is <= 5 ms per sweep on one core. Ground labelling (shared with the odometry and
// the boundary module) is timed apart.
#include <benchmark/benchmark.h>

#include "roadslam/objects/tracker.h"
#include "roadslam/preprocess/ground_segmentation.h"
#include "../tests/synthetic_boxes.h"

using namespace roadslam;
using namespace roadslam::objects;

namespace {

using Sweep = test::LabelledSweep;
const Sweep& sweep() { return test::streetSweep(); }

void BM_GroundLabels(benchmark::State& st) {
  const auto& s = sweep();
  for (auto _ : st) benchmark::DoNotOptimize(preprocess::segmentGroundWithHeights(s.scan.points, ClusterParams{}.ground));
  st.counters["points"] = static_cast<double>(s.scan.points.size());
}

void BM_ClusterAndTrack(benchmark::State& st) {
  const auto& s = sweep();
  ClusterParams p;
  p.method = static_cast<ClusterMethod>(st.range(0));
  TrackerParams tp;
  tp.motion_model = static_cast<MotionModel>(st.range(1));
  Tracker tr(tp);
  double t = 0;
  size_t objects = 0;
  for (auto _ : st) {
    const auto objs = segmentObjects(s.scan.points, true, s.g.ground, s.g.height_above_ground_m, p);
    tr.update(t += 0.1, Eigen::Isometry3d::Identity(), objs);
    objects = objs.size();
  }
  st.counters["objects"] = static_cast<double>(objects);
  st.SetLabel(toString(p.method) + " + " + toString(tp.motion_model));
}

}  // namespace

BENCHMARK(BM_GroundLabels)->Unit(benchmark::kMillisecond);
// method: 0 range image, 1 Euclidean, 2 DBSCAN; motion model: 0 CV, 1 CTRV, 2 IMM
BENCHMARK(BM_ClusterAndTrack)->Args({0, 0})->Args({1, 0})->Args({2, 0})->Args({0, 1})->Args({0, 2})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
