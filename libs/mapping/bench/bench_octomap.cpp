// Keyframe insertion into an OctoMap at 0.2 m: ours (OctoMapBuilder::insert) vs octomap's
// OcTree::insertPointCloud on the same cloud, with the agreement of the two maps, in one run on
// one core (CPU time of the inserting thread, so other load on the machine does not count):
//   taskset -c 1 build-*/bench/bench_mapping_octomap
// Clouds: a simulated VLP-16 sweep (urban-loop, 3 s in, deskewed with the true motion) and the first
// KITTI odometry sweep (HDL-64E, ~120k points) when ROADSLAM_SHARED_DATA holds it.
#include <benchmark/benchmark.h>

#include <octomap/OcTree.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

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

struct Keyframe {
  Cloud points_lidar;  ///< deskewed with the true motion, lidar frame [m]
  Eigen::Isometry3d T_map_lidar;
};

/// Every \p every-th sweep of a simulated urban-loop drive of \p duration_s, at its true pose.
std::vector<Keyframe> simDrive(double duration_s, size_t every) {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
  p.trajectory.start_standing_s = 0;
  p.duration_s = duration_s;
  sim::Simulator s(p);
  std::vector<Scan> sweeps;
  sim::SweepSink sink([&](Scan&& sc) { sweeps.push_back(std::move(sc)); });
  s.run(sink);
  std::vector<Keyframe> out;
  for (size_t i = sweeps.size() - 2;; i -= every) {  // the last full sweep first
    const Scan& sc = sweeps[i];
    const double t0 = sc.stamp_s - static_cast<double>(p.start_epoch_s);
    const auto T_world_lidar = toEigen(s.lidar().lidarPose(t0));
    const auto d = T_world_lidar.inverse() * toEigen(s.lidar().lidarPose(t0 + 0.1));
    Keyframe kf{{}, T_world_lidar};
    for (const auto& q : odometry::deskew(sc, d, 0.1)) kf.points_lidar.push_back(q.cast<float>());
    out.push_back(std::move(kf));
    if (i < 1 + every) break;
  }
  return out;
}

const std::vector<Keyframe>& drive() {
  static const std::vector<Keyframe> kfs = simDrive(6.0, 3);
  return kfs;
}

Cloud simCloud() { return simDrive(3.0, 1000).front().points_lidar; }

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

double threadCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

struct Figures {
  double wall_ms = 0, cpu_ms = 0;  ///< mean per insertion [ms]
  mapping::InsertStats last;
};
std::map<std::pair<int, int>, Figures> g_fig;  // (cloud, variant) -> figures
enum Variant { kOurs = 0, kOctomap = 1, kOursShipped = 2 };

// One keyframe into an empty map per iteration; the tree is not materialised (numVoxels()).
void BM_Insert(benchmark::State& state, Variant v) {
  const int which = static_cast<int>(state.range(0));
  const Cloud& c = cloud(which);
  if (c.empty()) {
    state.SkipWithError("cloud missing (KITTI data not found)");
    return;
  }
  Figures f;
  size_t n = 0;
  for (auto _ : state) {
    state.PauseTiming();
    mapping::OctoMapBuilder b(v == kOursShipped ? mapping::OctoMapParams{} : sameAsOctomap());
    state.ResumeTiming();
    const double cpu0 = threadCpuMs();
    f.last = v == kOctomap ? b.insertReference(c, Eigen::Isometry3d::Identity()) : b.insert(c, Eigen::Isometry3d::Identity());
    f.cpu_ms += threadCpuMs() - cpu0;
    f.wall_ms += f.last.ms;
    ++n;
    benchmark::DoNotOptimize(b.numVoxels());
  }
  f.cpu_ms /= static_cast<double>(std::max<size_t>(n, 1));
  f.wall_ms /= static_cast<double>(std::max<size_t>(n, 1));
  state.counters["points"] = static_cast<double>(c.size());
  state.counters["cpu_ms"] = f.cpu_ms;
  g_fig[{which, v}] = f;
}

// Materialising the octomap tree from the grid: once per map read (writeBt/writeOt/tree()).
void BM_TreeFromGrid(benchmark::State& state) {
  const Cloud& c = cloud(static_cast<int>(state.range(0)));
  if (c.empty()) {
    state.SkipWithError("cloud missing (KITTI data not found)");
    return;
  }
  for (auto _ : state) {
    state.PauseTiming();
    mapping::OctoMapBuilder b(sameAsOctomap());
    b.insert(c, Eigen::Isometry3d::Identity());
    state.ResumeTiming();
    benchmark::DoNotOptimize(b.numLeafs());
  }
}

// The drive's keyframes one after the other into one growing map (the run's case): mean per keyframe.
std::map<int, Figures> g_drive;                                 // variant -> figures
std::map<int, std::unique_ptr<mapping::OctoMapBuilder>> g_drive_map;  // variant -> last map built
void BM_Drive(benchmark::State& state) {
  const auto v = static_cast<Variant>(state.range(0));
  const auto& kfs = drive();
  Figures f;
  size_t n = 0;
  for (auto _ : state) {
    state.PauseTiming();
    auto b = std::make_unique<mapping::OctoMapBuilder>(v == kOursShipped ? mapping::OctoMapParams{} : sameAsOctomap());
    state.ResumeTiming();
    for (const auto& kf : kfs) {
      const double cpu0 = threadCpuMs();
      const auto st = v == kOctomap ? b->insertReference(kf.points_lidar, kf.T_map_lidar) : b->insert(kf.points_lidar, kf.T_map_lidar);
      f.cpu_ms += threadCpuMs() - cpu0;
      f.wall_ms += st.ms;
      ++n;
    }
    benchmark::DoNotOptimize(b->numVoxels());
    g_drive_map[v] = std::move(b);
  }
  f.cpu_ms /= static_cast<double>(std::max<size_t>(n, 1));
  f.wall_ms /= static_cast<double>(std::max<size_t>(n, 1));
  state.counters["keyframes"] = static_cast<double>(kfs.size());
  state.counters["cpu_ms_per_kf"] = f.cpu_ms;
  g_drive[v] = f;
}
BENCHMARK(BM_Drive)->Arg(kOurs)->Arg(kOursShipped)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Drive)->Arg(kOctomap)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void reportDrive() {
  if (!g_drive.count(kOurs) || !g_drive.count(kOctomap)) return;
  const mapping::OctoMapBuilder &ours = *g_drive_map[kOurs], &ref = *g_drive_map[kOctomap];
  const auto a = mapping::compareOctoMaps(ref.tree(), ours.tree());
  const Figures &o = g_drive[kOurs], &r = g_drive[kOctomap];
  std::printf("sim VLP-16 drive, %zu keyframes into one map (0.2 m, max range 60 m, free space to 60 m), per keyframe:\n"
              "  ours %.1f ms CPU (%.1f ms wall), octomap insertPointCloud %.1f ms CPU (%.1f ms wall): ratio %.1fx CPU\n"
              "  final maps: occupied %.1f %% of %zu, free %.1f %% of %zu, ours not in octomap %zu; grid %.1f MB for %zu voxels\n",
              drive().size(), o.cpu_ms, o.wall_ms, r.cpu_ms, r.wall_ms, r.cpu_ms / std::max(o.cpu_ms, 1e-9),
              a.occupied_percent, a.ref_occupied, a.free_percent, a.ref_free, a.other_unknown,
              static_cast<double>(ours.gridBytes()) / 1e6, ours.numVoxels());
  if (g_drive.count(kOursShipped)) {
    std::printf("  shipped [octomap] (free space to 10 m): ours %.1f ms CPU (%.1f ms wall) per keyframe\n",
                g_drive[kOursShipped].cpu_ms, g_drive[kOursShipped].wall_ms);
  }
}

void BM_Ours(benchmark::State& s) { BM_Insert(s, kOurs); }
void BM_Octomap(benchmark::State& s) { BM_Insert(s, kOctomap); }
void BM_OursShippedIni(benchmark::State& s) { BM_Insert(s, kOursShipped); }
BENCHMARK(BM_Ours)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Octomap)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OursShippedIni)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TreeFromGrid)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void report() {
  for (int which = 0; which < 2; ++which) {
    const Cloud& c = cloud(which);
    if (c.empty() || !g_fig.count({which, kOurs}) || !g_fig.count({which, kOctomap})) continue;
    mapping::OctoMapBuilder ours(sameAsOctomap()), ref(sameAsOctomap());
    ours.insert(c, Eigen::Isometry3d::Identity());
    ref.insertReference(c, Eigen::Isometry3d::Identity());
    const auto a = mapping::compareOctoMaps(ref.tree(), ours.tree());
    const double grid_mb = static_cast<double>(ours.gridBytes()) / 1e6;
    const size_t voxels = ours.numVoxels(), leafs = ours.numLeafs();
    const Figures &o = g_fig[{which, kOurs}], &r = g_fig[{which, kOctomap}];
    std::printf("%s (%zu points, 0.2 m, max range 60 m, free space to 60 m as octomap), per keyframe:\n"
                "  ours %.1f ms CPU (%.1f ms wall), octomap insertPointCloud %.1f ms CPU (%.1f ms wall): "
                "ratio %.1fx CPU, %.1fx wall\n"
                "  ours: %zu ray cells, %zu free + %zu occupied voxels; agreement over octomap's leaves: "
                "occupied %.1f %% of %zu, free %.1f %% of %zu, ours not in octomap %zu\n",
                name(which), c.size(), o.cpu_ms, o.wall_ms, r.cpu_ms, r.wall_ms, r.cpu_ms / std::max(o.cpu_ms, 1e-9),
                r.wall_ms / std::max(o.wall_ms, 1e-9), o.last.ray_cells, o.last.free_keys, o.last.occupied_keys,
                a.occupied_percent, a.ref_occupied, a.free_percent, a.ref_free, a.other_unknown);
    std::printf("  ours: grid %.1f MB for %zu voxels; materialised octree %zu leaves (pruned)\n", grid_mb, voxels,
                leafs);
    if (g_fig.count({which, kOursShipped})) {
      const Figures& s = g_fig[{which, kOursShipped}];
      std::printf("  shipped [octomap] (free space to 10 m): ours %.1f ms CPU (%.1f ms wall), %zu ray cells\n",
                  s.cpu_ms, s.wall_ms, s.last.ray_cells);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  report();
  reportDrive();
  benchmark::Shutdown();
  return 0;
}
