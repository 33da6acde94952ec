// Open time of a rawlog with and without its cached index, and the latency of a jump to a time
// (findAtTime + load of that observation), as a table. Make a big rawlog with the simulator:
//   build/bin/roadslam-sim --config ini/sim/urban-loop.ini --duration 600 --out /tmp/sim600
//   build/bin/roadslam-rawlog convert /tmp/sim600/velodyne.pcap /tmp/big600.rawlog
//   build/bench/bench_rawlog_index /tmp/big600.rawlog [jumps]
#include <sys/resource.h>

#include <mrpt/obs/CObservation.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <thread>

#include "roadslam/rawlog/background_rawlog_index.h"
#include "roadslam/rawlog/rawlog_index.h"

using roadslam::rawlog::BackgroundRawlogIndex;
using roadslam::rawlog::RawlogIndex;
using roadslam::rawlog::RawlogIndexOptions;
using Clock = std::chrono::steady_clock;

namespace {
double ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }
double pct(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(p * double(v.size())))];
}
double peakRss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s RAWLOG [jumps=200]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const int jumps = argc > 2 ? std::stoi(argv[2]) : 200;
  RawlogIndexOptions build;
  build.use_cache = false;  // index from scratch, and write the sidecar
  {
    // As the viewer opens a rawlog it has never seen: indexing on a thread; the first sweep can be
    // shown as soon as it is indexed, the timeline grows while the rest is.
    const auto tb = Clock::now();
    auto bg = BackgroundRawlogIndex::open(path, build);
    std::optional<double> first_ms, sweep_ms;
    while (!bg->done()) {
      bg->poll();
      if (!first_ms && bg->size() > 0) first_ms = ms(Clock::now() - tb);
      for (std::size_t i = 0; !sweep_ms && i < bg->size(); ++i)
        if (bg->className(i) == "CObservationVelodyneScan" || bg->className(i) == "CObservationPointCloud") {
          bg->load(i);
          sweep_ms = ms(Clock::now() - tb);
        }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    std::printf("background open   first observation listed after %.1f ms, first sweep loaded after %.1f ms, "
                "whole index after %.0f ms\n",
                first_ms.value_or(-1), sweep_ms.value_or(-1), ms(Clock::now() - tb));
  }
  const auto t0 = Clock::now();
  auto idx = RawlogIndex::open(path, build);
  const double build_ms = ms(Clock::now() - t0);
  const double rss_build = peakRss_mb();
  const double duration_s = idx->lastStamp() - idx->firstStamp();
  std::printf("rawlog            %s\n", path.c_str());
  std::printf("size              %.1f MB on disk, %.1f MB uncompressed, %s\n",
              double(std::filesystem::file_size(path)) / 1e6, double(idx->uncompressedBytes()) / 1e6,
              idx->gzip() ? "gzip" : "plain");
  std::printf("observations      %zu over %.1f s (%.1f min), %zu access points\n", idx->size(),
              duration_s, duration_s / 60, idx->accessPoints());
  std::printf("sidecar           %.2f MB\n",
              double(std::filesystem::file_size(RawlogIndex::sidecarPath(path))) / 1e6);
  std::printf("open, no index    %.0f ms (index built and written; peak RSS %.0f MB)\n", build_ms, rss_build);
  idx.reset();

  std::vector<double> open_ms;
  for (int k = 0; k < 5; ++k) {
    const auto t1 = Clock::now();
    idx = RawlogIndex::open(path);
    open_ms.push_back(ms(Clock::now() - t1));
    if (!idx->openInfo().from_cache) std::printf("  (sidecar not used: %s)\n", idx->openInfo().cache_note.c_str());
  }
  std::printf("open, cached      %.1f ms median of 5 (min %.1f, max %.1f)\n", pct(open_ms, 0.5),
              *std::min_element(open_ms.begin(), open_ms.end()),
              *std::max_element(open_ms.begin(), open_ms.end()));

  std::mt19937 rng(1);
  std::uniform_real_distribution<double> at(idx->firstStamp(), idx->lastStamp());
  std::vector<double> jump_ms;
  std::size_t bytes = 0;
  for (int k = 0; k < jumps; ++k) {
    const auto t1 = Clock::now();
    const auto i = idx->findAtTime(at(rng));
    const auto obs = idx->load(*i);
    jump_ms.push_back(ms(Clock::now() - t1));
    bytes += idx->entry(*i).size;
  }
  std::printf("jump to a time    %.1f ms median, %.1f p95, %.1f max over %d random times (%.0f kB per observation)\n",
              pct(jump_ms, 0.5), pct(jump_ms, 0.95), *std::max_element(jump_ms.begin(), jump_ms.end()), jumps,
              double(bytes) / jumps / 1e3);
  std::vector<double> step_ms;
  const std::size_t from = idx->size() / 2;
  for (std::size_t i = from; i < std::min(idx->size(), from + 50); ++i) {
    const auto t1 = Clock::now();
    idx->load(i);
    step_ms.push_back(ms(Clock::now() - t1));
  }
  if (!step_ms.empty())
    std::printf("step to the next  %.1f ms median, %.1f max (50 in a row)\n", pct(step_ms, 0.5),
                *std::max_element(step_ms.begin(), step_ms.end()));
  std::printf("peak RSS          %.0f MB\n", peakRss_mb());
  return 0;
}
