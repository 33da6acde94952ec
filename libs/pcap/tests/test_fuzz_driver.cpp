// Deterministic fuzzing for CI with gcc: fixed-seed mutations of a valid capture fed to the
// libFuzzer entry point. Passing = no crash, no sanitizer report, within the iteration budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "pcap_test_util.h"
#include "roadslam/pcap/pcap_writer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size);

TEST(FuzzPcapReader, MutatedCapturesNeverCrash) {
  const std::string path = roadslam::pcap::test::tempPath("fuzz_seed.pcap");
  {
    roadslam::pcap::PcapWriter w(path);
    std::vector<uint8_t> payload(200, 0x5A);
    for (int i = 0; i < 3; ++i) w.writeUdp(100.0 + i, 2368, 2368, payload.data(), payload.size());
  }
  const std::vector<uint8_t> seed = roadslam::pcap::test::readFile(path);
  std::remove(path.c_str());
  ASSERT_GT(seed.size(), 24u);
  std::mt19937 rng(4242);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(8);
  int runs = 0;
  for (; runs < 5000 && std::chrono::steady_clock::now() < deadline; ++runs) {
    std::vector<uint8_t> in = seed;
    const int edits = 1 + static_cast<int>(rng() % 8);
    for (int e = 0; e < edits; ++e) {
      // Bias edits to the headers (global, record, Ethernet/IP/UDP) where parsing decisions live.
      const std::size_t at = rng() % 2 ? rng() % std::min<std::size_t>(in.size(), 90) : rng() % in.size();
      switch (rng() % 4) {
        case 0: in[at] = static_cast<uint8_t>(rng()); break;
        case 1: in[at] ^= static_cast<uint8_t>(1u << (rng() % 8)); break;
        case 2: in.resize(std::max<std::size_t>(1, rng() % in.size())); break;
        default: in[at] = rng() % 2 ? 0xFF : 0x00; break;
      }
    }
    LLVMFuzzerTestOneInput(in.data(), in.size());
  }
  std::cout << runs << " mutated captures read\n";
  EXPECT_GT(runs, 100);
}
