// Keyframe insertion into an OctoMap at 0.2 m: ours (OctoMapBuilder::insert) vs octomap's
// OcTree::insertPointCloud on the same cloud, with the agreement of the two maps, in one run:
//   build-*/bench/bench_mapping_octomap
// Clouds: a simulated VLP-16 sweep (urban-loop, 3 s in, deskewed with the true motion) and the first
// KITTI odometry sweep (HDL-64E, ~120k points) when ROADSLAM_SHARED_DATA holds it.
#include <benchmark/benchmark.h>

#include <octomap/OcTree.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/mapping/octo_map.h"
#include "roadslam/odometry/deskew.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/sim/eigen.h"
#include "roadslam/sim/sweep_sink.h"
#include "roadslam/velodyne/packet.h"

using namespace roadslam;
using Cloud = std::vector<Eigen::Vector3f>;

namespace {

using sim::toEigen;

Cloud simCloud() {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
  p.trajectory.start_standing_s = 0;
  p.duration_s = 3.0;
  sim::Simulator s(p);
  std::vector<Scan> sweeps;
  sim::SweepSink sink([&](Scan&& sc) { sweeps.push_back(std::move(sc)); });
  s.run(sink);
  const Scan& sc = sweeps.at(sweeps.size() - 2);
  const double t0 = sc.stamp_s - static_cast<double>(p.start_epoch_s);
  const auto d = toEigen(s.lidar().lidarPose(t0)).inverse() * toEigen(s.lidar().lidarPose(t0 + 0.1));
  Cloud out;
  for (const auto& q : odometry::deskew(sc, d, 0.1)) out.push_back(q.cast<float>());
  return out;
}

Cloud kittiCloud() {
  const std::string f = std::string(ROADSLAM_SHARED_DATA) + "/kitti/odometry-00-first16/velodyne/000000.bin";
  Cloud out;
  if (!std::filesystem::exists(f)) return out;
  for (const auto& q : datasets::readKittiBin(f).points) out.emplace_back(q.x, q.y, q.z);
  return out;
}

const Cloud& cloud(int which) {
  static const Cloud sim = simCloud(), kitti = kittiCloud();
  return which == 0 ? sim : kitti;
}
// free space cleared over the whole max range, as octomap does: the agreement compares like with like
mapping::OctoMapParams sameAsOctomap() {
  mapping::OctoMapParams p;
  p.free_max_range_m = p.max_range_m;
  return p;
}

const char* name(int which) { return which == 0 ? "sim VLP-16" : "KITTI HDL-64E"; }

std::map<std::pair<int, bool>, double> g_ms;  // (cloud, ours) -> mean ms per insertion

void BM_Insert(benchmark::State& state, bool ours) {
  const int which = static_cast<int>(state.range(0));
  const Cloud& c = cloud(which);
  if (c.empty()) {
    state.SkipWithError("cloud missing (KITTI data not found)");
    return;
  }
  double total_ms = 0;
  size_t n = 0;
  for (auto _ : state) {
    state.PauseTiming();
    mapping::OctoMapBuilder b(sameAsOctomap());
    state.ResumeTiming();
    const auto st = ours ? b.insert(c, Eigen::Isometry3d::Identity()) : b.insertReference(c, Eigen::Isometry3d::Identity());
    total_ms += st.ms;
    ++n;
    benchmark::DoNotOptimize(b.numLeafs());
  }
  state.counters["points"] = static_cast<double>(c.size());
  g_ms[{which, ours}] = total_ms / std::max<size_t>(n, 1);
}

void BM_Ours(benchmark::State& s) { BM_Insert(s, true); }
void BM_Octomap(benchmark::State& s) { BM_Insert(s, false); }
BENCHMARK(BM_Ours)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Octomap)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void report() {
  for (int which = 0; which < 2; ++which) {
    const Cloud& c = cloud(which);
    if (c.empty()) continue;
    mapping::OctoMapBuilder ours(sameAsOctomap()), ref(sameAsOctomap());
    ours.insert(c, Eigen::Isometry3d::Identity());
    ref.insertReference(c, Eigen::Isometry3d::Identity());
    const auto a = mapping::compareOctoMaps(ref.tree(), ours.tree());
    const double mo = g_ms[{which, true}], mr = g_ms[{which, false}];
    std::printf("%s (%zu points, 0.2 m, max range 60 m): ours %.1f ms, octomap insertPointCloud %.1f ms, "
                "speed-up %.1fx; agreement over octomap's leaves: occupied %.1f %% of %zu, free %.1f %% of %zu\n",
                name(which), c.size(), mo, mr, mr / std::max(mo, 1e-9), a.occupied_percent, a.ref_occupied,
                a.free_percent, a.ref_free);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  report();
  benchmark::Shutdown();
  return 0;
}
