// Registration against its peers: same 50 consecutive pairs of the KITTI raw drive 2011_09_26_0001, same
// 0.5 m voxel clouds (~11k points), identity initial guess, one thread: ours (ICP point-to-plane, NDT),
// MRPT CICP::Align3D, and with -DROADSLAM_BENCH_PEERS=ON PCL NDT, PCL GICP and Open3D point-to-plane.
// Time = process CPU time of everything from the clouds to the pose (all threads counted; OpenMP is
// pinned to one thread). Error = translation / rotation of T_gt^-1 * T_est against the OXTS relative
// pose. Prints the table and writes it as CSV (--csv=FILE, default bench_peers.csv).
//   taskset -c 1 build/bench/bench_peers --csv=peers.csv
#include <benchmark/benchmark.h>
#include <roadslam/common/atomic_file.h>
#include <roadslam/datasets/kitti_scans.h>
#include <roadslam/datasets/trajectory_io.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>
#include <numeric>
#include <sstream>

#include "peers.h"

namespace {
namespace rb = roadslam::bench;
namespace reg = roadslam::registration;
namespace ds = roadslam::datasets;

constexpr int kPairs = 50;
constexpr double kVoxel_m = 0.5;
constexpr double kOff_m = 0.3;  // a pair this far off counts as failed [m]
const std::string kRaw = std::string(ROADSLAM_SHARED_DATA) + "/kitti/raw-2011_09_26-0001/";

struct Data {
  std::vector<reg::PointCloud> clouds;  // voxelized sweeps, velodyne frame [m]
  ds::PoseList T_world_velo;            // OXTS ground truth
  bool ok = false;
};

const Data& data() {
  static const Data d = [] {
    Data out;
    if (!std::filesystem::exists(kRaw + "velodyne.tar.zst")) return out;
    const std::string dir = ds::unpackTarZstOnce(kRaw + "velodyne.tar.zst", PEERS_BENCH_CACHE);
    const ds::KittiScanFolder folder(dir + "/velodyne");
    out.T_world_velo = ds::readKittiPoses(kRaw + "poses_velo_kitti.txt");
    for (size_t i = 0; i <= kPairs; ++i) out.clouds.push_back(reg::voxelDownsample(reg::toPointCloud(folder.read(i)), kVoxel_m));
    out.ok = true;
    return out;
  }();
  return d;
}

double processCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

struct Row {
  std::string settings;
  std::vector<double> ms, terr_m, rerr_deg;
  int not_converged = 0;
};
std::map<std::string, Row>& rows() {
  static std::map<std::string, Row> r;
  return r;
}
std::vector<std::string>& order() {
  static std::vector<std::string> o;
  return o;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
double mean(const std::vector<double>& v) { return v.empty() ? 0 : std::accumulate(v.begin(), v.end(), 0.0) / v.size(); }
double maxOf(const std::vector<double>& v) { return v.empty() ? 0 : *std::max_element(v.begin(), v.end()); }
int countOff(const std::vector<double>& v) {
  return static_cast<int>(std::count_if(v.begin(), v.end(), [](double e) { return e > kOff_m; }));
}

void runPeer(benchmark::State& state, rb::PeerMethod* m) {
  if (!data().ok) return state.SkipWithError(("missing " + kRaw + "velodyne.tar.zst").c_str());
  Row& row = rows()[m->name()];
  row = {};
  row.settings = m->settings();
  size_t pair = 0;
  for (auto _ : state) {
    const auto& d = data();
    m->prepare(d.clouds[pair], d.clouds[pair + 1]);  // target = sweep i, source = sweep i+1
    const double t0 = processCpuMs();
    const rb::PeerResult r = m->run();
    row.ms.push_back(processCpuMs() - t0);
    const Eigen::Isometry3d gt = d.T_world_velo[pair].inverse() * d.T_world_velo[pair + 1];
    const Eigen::Isometry3d E = gt.inverse() * r.T_target_source;
    row.terr_m.push_back(E.translation().norm());
    row.rerr_deg.push_back(Eigen::AngleAxisd(E.linear()).angle() * 180.0 / M_PI);
    row.not_converged += r.converged ? 0 : 1;
    pair = (pair + 1) % kPairs;
  }
  state.counters["median_ms"] = median(row.ms);
  state.counters["median_terr_m"] = median(row.terr_m);
  state.counters["max_terr_m"] = maxOf(row.terr_m);
  state.counters["pairs_off_0.3m"] = countOff(row.terr_m);
}

// The table, also as CSV. Ratios: this method's median time / error over ours (point-to-plane, NDT).
std::string table(const char* sep, bool pad) {
  std::ostringstream os;
  const char* cols[] = {"method", "pairs", "median_ms", "mean_ms", "median_terr_m", "mean_terr_m", "max_terr_m",
                        "median_rerr_deg", "pairs_off_0.3m", "not_converged", "ms_vs_ours_p2pl", "ms_vs_ours_ndt",
                        "terr_vs_ours_p2pl", "terr_vs_ours_ndt"};
  char buf[64];
  for (size_t i = 0; i < std::size(cols); ++i) {
    std::snprintf(buf, sizeof buf, pad ? (i == 0 ? "%-26s" : "%18s") : "%s", cols[i]);
    os << (i ? sep : "") << buf;
  }
  os << "\n";
  const auto ref = [](const std::string& n) { return rows().count(n) ? &rows()[n] : nullptr; };
  const Row* p2pl = ref("ours_icp_point_to_plane");
  const Row* ndt = ref("ours_ndt");
  const auto ratio = [](double a, const Row* r, bool time) {
    const double b = r ? (time ? median(r->ms) : median(r->terr_m)) : 0;
    return b > 0 ? a / b : 0;
  };
  for (const auto& name : order()) {
    const Row& r = rows()[name];
    if (r.ms.empty()) continue;
    const double vals[] = {static_cast<double>(r.ms.size()), median(r.ms), mean(r.ms), median(r.terr_m), mean(r.terr_m),
                           maxOf(r.terr_m), median(r.rerr_deg), static_cast<double>(countOff(r.terr_m)),
                           static_cast<double>(r.not_converged), ratio(median(r.ms), p2pl, true),
                           ratio(median(r.ms), ndt, true), ratio(median(r.terr_m), p2pl, false),
                           ratio(median(r.terr_m), ndt, false)};
    std::snprintf(buf, sizeof buf, pad ? "%-26s" : "%s", name.c_str());
    os << buf;
    for (size_t i = 0; i < std::size(vals); ++i) {
      std::snprintf(buf, sizeof buf, pad ? "%18.4g" : "%.6g", vals[i]);
      os << sep << buf;
    }
    os << "\n";
  }
  return os.str();
}

// OpenMP (Open3D, PCL) reads OMP_NUM_THREADS when its library loads: set it and start again.
void pinOpenMpToOneThread(char** argv) {
  const char* v = std::getenv("OMP_NUM_THREADS");
  if (v && std::strcmp(v, "1") == 0) return;
  setenv("OMP_NUM_THREADS", "1", 1);
  execv("/proc/self/exe", argv);
  std::perror("bench_peers: re-exec with OMP_NUM_THREADS=1 failed, continuing");
}

}  // namespace

int main(int argc, char** argv) {
  pinOpenMpToOneThread(argv);
  std::string csv = "bench_peers.csv";
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--csv=", 6) == 0) csv = argv[i] + 6;
  }
  benchmark::Initialize(&argc, argv);
  rb::PeerList peers;
  rb::addOurs(peers);
  rb::addMrpt(peers);
  rb::addPcl(peers);
  rb::addOpen3d(peers);
  for (const auto& p : peers) {
    order().push_back(p->name());
    benchmark::RegisterBenchmark(p->name().c_str(), runPeer, p.get())->Iterations(kPairs)->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  std::printf("\nKITTI raw 2011_09_26_0001, pairs (i, i+1) i = 0..%d, %.1f m voxels, identity guess, CPU ms per alignment\n",
              kPairs - 1, kVoxel_m);
  std::printf("%s\n", table(" ", true).c_str());
  for (const auto& p : peers) {
    if (!rows()[p->name()].ms.empty()) std::printf("  %-26s %s\n", p->name().c_str(), p->settings().c_str());
  }
  roadslam::writeFileAtomically(csv, table(",", false));
  std::printf("table written to %s\n", csv.c_str());
  benchmark::Shutdown();
  return 0;
}
