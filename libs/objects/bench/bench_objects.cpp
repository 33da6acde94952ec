// Clustering + tracking per sweep on a ray-cast VLP-16 street (8 cars/poles, ~20k points): the
// budget is <= 5 ms per sweep on one core. Ground labelling (shared with the odometry and
// the boundary module) is timed apart.
#include <benchmark/benchmark.h>

#include "roadslam/objects/free_space.h"
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

/// The moving label's free-space evidence per sweep (ObjectsStage with free_space_lag_s > 0): the
/// sweep's range image kept, and every object's points (at most 64) checked against the one of 1 s before.
void BM_FreeSpace(benchmark::State& st) {
  const auto& s = sweep();
  const auto objs = segmentObjects(s.scan.points, true, s.g.ground, s.g.height_above_ground_m, ClusterParams{});
  std::vector<std::vector<Eigen::Vector3d>> pts;
  for (const Object& o : objs) pts.push_back(samplePointsInMap(s.scan, o.indices, Eigen::Isometry3d::Identity()));
  FreeSpaceHistory h;
  double t = 0;
  int evidence = 0;
  for (auto _ : st) {
    for (const auto& p : pts) {
      const FreeEvidence e = h.check(p, t, 1.0, 0.5);
      evidence += e.through + e.hit;
    }
    h.add(s.scan, Eigen::Isometry3d::Identity(), t);
    t += 0.1;
  }
  benchmark::DoNotOptimize(evidence);
  st.counters["objects"] = static_cast<double>(objs.size());
}

}  // namespace

BENCHMARK(BM_FreeSpace)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GroundLabels)->Unit(benchmark::kMillisecond);
// method: 0 range image, 1 Euclidean, 2 DBSCAN; motion model: 0 CV, 1 CTRV, 2 IMM
BENCHMARK(BM_ClusterAndTrack)->Args({0, 0})->Args({1, 0})->Args({2, 0})->Args({0, 1})->Args({0, 2})->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
