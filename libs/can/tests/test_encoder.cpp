// Encoder: decode(encode(x)) == x within one LSB on random layouts (checked by the bit-by-bit
// reference decoder, other payload bits untouched), clamping, and hand-computed frames.
#include "encoder_check.h"
#include "reference_decoder.h"

#include <roadslam/can/encoder.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace roadslam::can;

namespace {
Signal randomLayout(std::mt19937_64& rng, unsigned bytes) {
  Signal s;
  s.name = "S";
  s.little_endian = rng() % 2;
  s.is_signed = rng() % 2;
  s.length = 1 + static_cast<std::uint32_t>(rng() % 52);
  const unsigned bits = bytes * 8;
  if (s.little_endian) {
    s.start_bit = static_cast<std::uint32_t>(rng() % (bits - s.length + 1));
  } else {
    const unsigned msb_lin = static_cast<unsigned>(rng() % (bits - s.length + 1));
    s.start_bit = (msb_lin / 8) * 8 + 7 - msb_lin % 8;
  }
  s.factor = (rng() % 2) ? 1.0 : 0.01 * static_cast<double>(1 + rng() % 100);
  s.offset = (rng() % 2) ? 0.0 : -100.0 + static_cast<double>(rng() % 2000) * 0.1;
  return s;
}
}  // namespace

TEST(Encoder, RoundTripWithinOneLsbAndOtherBitsUntouched) {
  std::mt19937_64 rng(4242);
  for (int trial = 0; trial < 3000; ++trial) {
    const unsigned bytes = trial % 5 == 0 ? 64 : 8;
    const Signal s = randomLayout(rng, bytes);
    const SignalPlan p = makeSignalPlan(s);
    CanFrame f;
    f.len = static_cast<std::uint8_t>(bytes);
    for (unsigned b = 0; b < bytes; ++b) f.data[b] = static_cast<std::uint8_t>(rng());
    const CanFrame before = f;
    const double x = test::randomPhysical(s, rng);
    ASSERT_TRUE(encodePhysical(p, x, f));
    const auto back = test::referencePhysical(s, f);
    ASSERT_TRUE(back.has_value());
    EXPECT_LE(std::abs(*back - x), 0.5 * s.factor + 1e-9 * std::abs(x))
        << "trial " << trial << " start " << s.start_bit << " len " << s.length
        << (s.little_endian ? " intel" : " motorola") << (s.is_signed ? " signed" : " unsigned");
    const auto mine = test::signalBits(s);
    for (unsigned b = 0; b < bytes * 8; ++b) {
      if (mine.count(b)) continue;
      ASSERT_EQ((f.data[b / 8] >> (b % 8)) & 1U, (before.data[b / 8] >> (b % 8)) & 1U)
          << "trial " << trial << ": bit " << b << " outside the signal changed";
    }
  }
}

TEST(Encoder, ClampsToTheRawRangeAndRefusesShortFrames) {
  Signal s;
  s.start_bit = 8;
  s.length = 8;
  s.is_signed = true;
  s.factor = 0.5;
  const SignalPlan p = makeSignalPlan(s);
  CanFrame f;
  f.len = 8;
  ASSERT_TRUE(encodePhysical(p, 1000.0, f));
  EXPECT_EQ(f.data[1], 0x7F);  // +127 * 0.5
  ASSERT_TRUE(encodePhysical(p, -1000.0, f));
  EXPECT_EQ(f.data[1], 0x80);  // -128 * 0.5
  f.len = 1;
  EXPECT_FALSE(encodePhysical(p, 1.0, f));
}

// Frames computed by hand from the DBC definition (Vector DBC: Motorola start bit = MSB).
TEST(Encoder, HandCheckedFrame) {
  const Database db = parseDbc(R"(BO_ 170 WHEEL_SPEEDS: 8 XXX
 SG_ WHEEL_SPEED_FR : 7|16@0+ (0.01,-67.67) [0|250] "kmh" XXX
 SG_ TEMP : 16|10@1- (0.5,0) [-256|255] "C" XXX
 SG_ FLAG : 63|1@1+ (1,0) [0|1] "" XXX
)");
  const MessageEncoder enc(*db.findMessage("WHEEL_SPEEDS"));
  ASSERT_EQ(enc.size(), 3U);
  double v[3];
  v[enc.index("WHEEL_SPEED_FR")] = 10.0;  // raw (10 + 67.67) / 0.01 = 7767 = 0x1E57, MSB first
  v[enc.index("TEMP")] = -3.0;            // raw -6 = 0x3FA (10 bits): byte 2 = 0xFA, bits 24..25 = 0x3
  v[enc.index("FLAG")] = 1.0;             // bit 63 = MSB of byte 7
  CanFrame f;
  enc.encode(v, 1234567, f);
  EXPECT_EQ(f.id, 170U);
  EXPECT_EQ(f.len, 8);
  EXPECT_EQ(f.t_us, 1234567);
  const std::array<std::uint8_t, 8> want{0x1E, 0x57, 0xFA, 0x03, 0x00, 0x00, 0x00, 0x80};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(f.data[i], want[i]) << "byte " << i;
  const Decoder dec(db);
  double out[3];
  ASSERT_EQ(dec.decode(f, out, nullptr), DecodeStatus::kOk);
  EXPECT_NEAR(out[0], 10.0, 1e-9);
  EXPECT_DOUBLE_EQ(out[1], -3.0);
  EXPECT_DOUBLE_EQ(out[2], 1.0);
  EXPECT_THROW(enc.index("NOPE"), std::invalid_argument);
}
