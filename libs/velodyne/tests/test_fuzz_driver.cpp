// Deterministic fuzzing for CI with gcc: fixed-seed mutations of valid seed inputs fed to the
// libFuzzer entry point. Passing = no crash, no sanitizer report, within the iteration budget.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <vector>

#include "roadslam/velodyne/encoder.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size);

using namespace roadslam::velodyne;

namespace {

std::vector<std::vector<uint8_t>> seeds() {
  std::array<FiringSequence, kVlp16SequencesPerPacket> seq{};
  for (int q = 0; q < 24; ++q) {
    seq[q].azimuth_deg = 359.0 + 0.2 * q;
    for (int l = 0; l < 16; ++l) {
      seq[q].strongest[l] = {1.0f + q + 0.1f * l, static_cast<uint8_t>(l)};
      seq[q].last[l] = {2.0f + q, static_cast<uint8_t>(q)};
    }
  }
  std::vector<std::vector<uint8_t>> s;
  for (auto mode : {ReturnMode::Strongest, ReturnMode::Dual}) {
    const auto p = encodeVlp16Packet(seq, 3599999000u, mode);
    s.emplace_back(p.begin(), p.end());
  }
  const auto pos = encodePositionPacket(
      7, "$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2E");
  s.emplace_back(pos.begin(), pos.end());
  return s;
}

}  // namespace

TEST(FuzzDecoder, MutatedPacketsNeverCrash) {
  std::mt19937 rng(20240601);
  const auto seed_inputs = seeds();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(8);
  int runs = 0;
  for (; runs < 100000 && std::chrono::steady_clock::now() < deadline; ++runs) {
    std::vector<uint8_t> in = seed_inputs[rng() % seed_inputs.size()];
    const int kind = static_cast<int>(rng() % 4);
    const int edits = 1 + static_cast<int>(rng() % 16);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = in.empty() ? 0 : rng() % in.size();
      switch (kind) {
        case 0: if (!in.empty()) in[at] = static_cast<uint8_t>(rng()); break;
        case 1: if (!in.empty()) in[at] ^= static_cast<uint8_t>(1u << (rng() % 8)); break;
        case 2: in.resize(rng() % (in.size() + 2)); break;
        default: in.insert(in.begin() + static_cast<long>(at), static_cast<uint8_t>(rng())); break;
      }
    }
    LLVMFuzzerTestOneInput(in.data(), in.size());
  }
  LLVMFuzzerTestOneInput(nullptr, 0);
  std::cout << runs << " mutated inputs decoded\n";
  EXPECT_GT(runs, 100);
}
