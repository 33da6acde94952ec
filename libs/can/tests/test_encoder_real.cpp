// Encoder on every real DBC the oracle tests parse: for every integer signal of every message,
// random physical values (fixed seed) survive encode -> Decoder::decode within one LSB.
#include "encoder_check.h"

#include <roadslam/can/decoder.h>
#include <roadslam/can/encoder.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

using namespace roadslam::can;
namespace fs = std::filesystem;

namespace {
std::vector<std::string> dbcFiles() {
  const std::string data = ROADSLAM_SHARED_DATA;
  std::vector<std::string> out;
  for (const char* dir : {"/dbc", "/can/rav4-2017", "/can/civic-2019"}) {
    if (!fs::exists(data + dir)) continue;
    for (const auto& e : fs::directory_iterator(data + dir))
      if (e.path().extension() == ".dbc") out.push_back(e.path().string());
  }
  out.push_back(std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/roadslam-sim.dbc");
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

TEST(RealDbcEncoder, DecodeOfEncodeWithinOneLsbOnEveryDbc) {
  const auto files = dbcFiles();
  if (files.size() < 8) GTEST_SKIP() << "expected 7 DBC files under " << ROADSLAM_SHARED_DATA << "/dbc and /can/*/";
  std::mt19937_64 rng(99);
  std::size_t checked = 0;
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    const Database db = loadDbcFile(file);
    const Decoder dec(db);
    std::vector<double> out(512);
    for (const MessagePlan& plan : dec.plans()) {
      const Message& m = *plan.message;
      if (m.size > 64 || plan.signals.size() > out.size()) continue;
      // One signal per frame over random other bits: some real DBCs declare overlapping signals.
      for (std::size_t k = 0; k < plan.signals.size(); ++k) {
        const Signal& s = m.signals[plan.signal_index[k]];
        if (s.value_type != ValueType::kInteger || s.mux == MuxRole::kMultiplexed) continue;
        for (int rep = 0; rep < 5; ++rep) {
          CanFrame f;
          f.id = m.id();
          f.flags = static_cast<std::uint8_t>((m.extended() ? kExtended : 0) | (m.size > 8 ? kFd : 0));
          f.len = static_cast<std::uint8_t>(m.size);
          for (std::size_t b = 0; b < m.size; ++b) f.data[b] = static_cast<std::uint8_t>(rng());
          const double x = test::randomPhysical(s, rng);
          if (!encodePhysical(plan.signals[k], x, f)) continue;  // signal beyond the declared size
          dec.decode(plan, f, out.data());
          EXPECT_LE(std::abs(out[k] - x), 0.5 * std::abs(s.factor) + 1e-9 * std::abs(x))
              << m.name << "." << s.name << " " << s.start_bit << "|" << s.length;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(checked, 5000U);
}
