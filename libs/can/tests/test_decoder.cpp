// Decoder against the bit-by-bit reference decoder on random signal layouts and random frames.
#include "reference_decoder.h"

#include <roadslam/can/decoder.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace roadslam::can;

namespace {
Signal randomSignal(std::mt19937& rng, std::size_t payload_bytes, int k) {
  Signal s;
  s.name = "S" + std::to_string(k);
  s.little_endian = rng() % 2;
  s.is_signed = rng() % 2;
  s.length = 1 + rng() % 64;
  const unsigned bits = static_cast<unsigned>(payload_bytes * 8);
  if (s.length > bits) s.length = bits;
  if (s.little_endian) {
    s.start_bit = rng() % (bits - s.length + 1);
  } else {  // pick the linear MSB position, convert to the sawtooth start bit
    const unsigned msb_lin = rng() % (bits - s.length + 1);
    s.start_bit = (msb_lin / 8) * 8 + 7 - msb_lin % 8;
  }
  s.factor = (rng() % 2) ? 1.0 : 0.01 * (1 + rng() % 100);
  s.offset = (rng() % 2) ? 0.0 : -100.0 + (rng() % 2000) * 0.1;
  if (s.length == 32 && rng() % 4 == 0) s.value_type = ValueType::kFloat32;
  if (s.length == 64 && rng() % 2 == 0) s.value_type = ValueType::kFloat64;
  return s;
}

bool same(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }
}  // namespace

TEST(Decoder, AgreesWithBitByBitReferenceOnRandomLayouts) {
  std::mt19937 rng(1234);
  for (int trial = 0; trial < 200; ++trial) {
    const bool fd = trial % 4 == 0;
    const std::size_t bytes = fd ? 64 : 8;
    Database db;
    Message m;
    m.dbc_id = static_cast<std::uint32_t>(trial);
    m.name = "M";
    m.size = static_cast<std::uint32_t>(bytes);
    for (int k = 0; k < 8; ++k) m.signals.push_back(randomSignal(rng, bytes, k));
    db.messages.push_back(m);
    const Decoder dec(db);
    for (int n = 0; n < 50; ++n) {
      CanFrame f;
      f.id = m.dbc_id;
      f.flags = fd ? kFd : 0;
      f.len = static_cast<std::uint8_t>(n % 10 == 0 ? rng() % (bytes + 1) : bytes);  // some short frames
      for (std::size_t b = 0; b < f.len; ++b) f.data[b] = static_cast<std::uint8_t>(rng());
      double out[8];
      const MessagePlan* plan = nullptr;
      const DecodeStatus st = dec.decode(f, out, &plan);
      ASSERT_NE(plan, nullptr);
      bool any_missing = false;
      for (int k = 0; k < 8; ++k) {
        const auto ref = test::referencePhysical(m.signals[k], f);
        any_missing |= !ref;
        const double want = ref ? *ref : std::nan("");
        EXPECT_TRUE(same(out[k], want)) << "trial " << trial << " signal " << k << " start "
                                        << m.signals[k].start_bit << " len " << m.signals[k].length
                                        << (m.signals[k].little_endian ? " intel " : " motorola ") << out[k]
                                        << " vs " << want;
      }
      EXPECT_EQ(st, any_missing ? DecodeStatus::kShortFrame
                                : (f.len == bytes ? DecodeStatus::kOk : DecodeStatus::kDlcMismatch));
    }
  }
}

TEST(Decoder, MultiplexedSignalsOnlyWithTheirMuxValue) {
  const Database db = parseDbc(R"(BO_ 2566844926 EXT_MUX: 8 ECU2
 SG_ MUX M : 0|4@1+ (1,0) [0|15] "" ECU1
 SG_ A m0 : 8|8@1+ (1,0) [0|255] "" ECU1
 SG_ B m1 : 8|16@1- (0.1,-5) [0|0] "V" ECU1
)");
  const Decoder dec(db, {"EXT_MUX.A", "B"});
  CanFrame f;
  f.flags = kExtended;
  f.id = 2566844926U & 0x1FFFFFFFU;
  f.len = 8;
  f.data = {0x01, 0xFF, 0xFF};
  double out[2];
  ASSERT_EQ(dec.decode(f, out, nullptr), DecodeStatus::kOk);
  EXPECT_TRUE(std::isnan(out[0]));
  EXPECT_DOUBLE_EQ(out[1], -0.1 - 5);
  f.data[0] = 0x00;
  ASSERT_EQ(dec.decode(f, out, nullptr), DecodeStatus::kOk);
  EXPECT_DOUBLE_EQ(out[0], 255);
  EXPECT_TRUE(std::isnan(out[1]));
  f.flags = 0;  // same id as 11-bit frame: unknown
  EXPECT_EQ(dec.decode(f, out, nullptr), DecodeStatus::kUnknownId);
  f.flags = kExtended | kRemote;
  EXPECT_EQ(dec.decode(f, out, nullptr), DecodeStatus::kNotData);
  EXPECT_THROW(Decoder(db, {"NOPE"}), std::invalid_argument);
  EXPECT_EQ(dec.locate("EXT_MUX.B").second, 1U);
}
