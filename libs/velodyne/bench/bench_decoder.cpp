// Decoder throughput on the real VLP-16 sample (293 packets): ours vs MRPT's
// CObservationVelodyneScan::generatePointCloud on the same packets. Reports points/s and the
// points each produces per pass (MRPT decodes one firing of two, and drops < 1 m by default).
#include <benchmark/benchmark.h>

#include <mrpt/obs/CObservationVelodyneScan.h>

#include <cstring>
#include <fstream>

#include "roadslam/pcap/pcap_reader.h"
#include "roadslam/velodyne/decoder.h"

using namespace roadslam;
using namespace roadslam::velodyne;

namespace {

const std::vector<pcap::UdpDatagram>& packets() {
  static const std::vector<pcap::UdpDatagram> p = [] {
    const std::string path =
        std::string(ROADSLAM_SHARED_DATA) + "/velodyne/mrpt_sample_velodyne_vlp16_gps.pcap";
    if (!std::ifstream(path)) return std::vector<pcap::UdpDatagram>{};
    return pcap::readUdpDatagrams(path, kDefaultDataPort);
  }();
  return p;
}

void decodeOurs(benchmark::State& state, double min_range_m) {
  if (packets().empty()) return state.SkipWithError("missing mrpt_sample_velodyne_vlp16_gps.pcap");
  DecoderParams params;
  params.min_range_m = min_range_m;
  const Decoder dec(params);
  std::vector<ScanPoint> out;
  out.reserve(packets().size() * 384);
  for (auto _ : state) {
    out.clear();
    for (const auto& d : packets()) dec.decode(d.payload.data(), d.payload.size(), out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["points"] = static_cast<double>(out.size());
  state.counters["points/s"] = benchmark::Counter(
      static_cast<double>(out.size()) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Ours(benchmark::State& state) { decodeOurs(state, 0.0); }
void BM_Ours_MinRange1m(benchmark::State& state) { decodeOurs(state, 1.0); }

void BM_MrptGeneratePointCloud(benchmark::State& state) {
  if (packets().empty()) return state.SkipWithError("missing mrpt_sample_velodyne_vlp16_gps.pcap");
  mrpt::obs::CObservationVelodyneScan obs;
  obs.calibration = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration("VLP16");
  for (const auto& d : packets()) {
    mrpt::obs::CObservationVelodyneScan::TVelodyneRawPacket raw;
    std::memcpy(&raw, d.payload.data(), sizeof(raw));
    obs.scan_packets.push_back(raw);
  }
  for (auto _ : state) {
    obs.generatePointCloud();
    benchmark::DoNotOptimize(obs.point_cloud.x.data());
  }
  const double n = static_cast<double>(obs.point_cloud.x.size());
  state.counters["points"] = n;
  state.counters["points/s"] =
      benchmark::Counter(n * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_Ours)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Ours_MinRange1m)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MrptGeneratePointCloud)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
