// Encoder -> decoder round trips against the truth the packets were made from.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "roadslam/velodyne/decoder.h"
#include "synthetic.h"

using namespace roadslam;
using namespace roadslam::velodyne;

namespace {

double azimuthOf(const ScanPoint& p) {  // clockwise from forward, [0, 2pi)
  double a = std::atan2(-p.y, p.x);
  return a < 0 ? a + 2 * M_PI : a;
}
double rangeOf(const ScanPoint& p) { return std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z); }
double angleDiffDeg(double a, double b) {
  double d = std::fmod((a - b) * 180 / M_PI + 540.0, 360.0) - 180.0;
  return std::abs(d);
}

}  // namespace

TEST(Decoder, KnownFiringsRoundTrip) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> r(0.5, 120.0);
  std::array<FiringSequence, kVlp16SequencesPerPacket> seq{};
  const double deg_per_us = 3600.0 * 1e-6;  // 10 Hz
  for (int q = 0; q < 24; ++q) {
    seq[q].azimuth_deg = 350.0 + deg_per_us * q * 55.296;  // crosses 360 inside the packet
    for (int l = 0; l < 16; ++l) seq[q].strongest[l] = {static_cast<float>(r(rng)), static_cast<uint8_t>(q * 10 + l)};
  }
  const auto pkt = encodeVlp16Packet(seq, 42, ReturnMode::Strongest, Model::VLP16);
  const Decoder dec;
  std::vector<ScanPoint> out;
  PacketInfo info;
  ASSERT_EQ(dec.decode(pkt.data(), pkt.size(), out, &info), DecodeStatus::Ok);
  ASSERT_EQ(out.size(), 384u);  // both firings of all 12 blocks
  EXPECT_EQ(info.timestamp_us, 42u);
  EXPECT_EQ(info.model, Model::VLP16);
  const Calibration cal = Calibration::builtinVlp16();
  for (int q = 0; q < 24; ++q) {
    for (int l = 0; l < 16; ++l) {
      const ScanPoint& p = out[q * 16 + l];
      const double t_us = q * 55.296 + l * 2.304;
      const double true_az = (350.0 + deg_per_us * t_us) * M_PI / 180;
      EXPECT_NEAR(rangeOf(p), seq[q].strongest[l].range_m, 0.002) << q << "/" << l;
      EXPECT_LT(angleDiffDeg(azimuthOf(p), true_az), 0.01) << q << "/" << l;
      EXPECT_NEAR(std::asin(p.z / rangeOf(p)), cal.lasers[l].vertical_rad, 1e-5);
      EXPECT_EQ(p.ring, cal.lasers[l].ring);
      EXPECT_FLOAT_EQ(p.t, static_cast<float>(t_us * 1e-6));
      EXPECT_EQ(p.intensity, q * 10 + l);
      EXPECT_EQ(p.return_index, 0);
    }
  }
}

TEST(Decoder, AxisConventionAgainstVeloViewFormula) {
  // VeloView: x_vv = r cos(w) sin(a), y_vv = r cos(w) cos(a), z = r sin(w); ours: x = y_vv, y = -x_vv.
  for (double az_deg : {0.0, 45.0, 90.0, 180.0, 270.0}) {
    std::array<FiringSequence, kVlp16SequencesPerPacket> seq{};
    for (auto& s : seq) s.azimuth_deg = az_deg;
    seq[0].strongest[0] = {10.0f, 1};  // laser 0: -15 deg
    const auto pkt = encodeVlp16Packet(seq, 0);
    const Decoder dec;
    std::vector<ScanPoint> out;
    ASSERT_EQ(dec.decode(pkt.data(), pkt.size(), out), DecodeStatus::Ok);
    ASSERT_EQ(out.size(), 1u);
    const double a = az_deg * M_PI / 180, w = -15 * M_PI / 180;
    EXPECT_NEAR(-out[0].y, 10 * std::cos(w) * std::sin(a), 1e-4) << az_deg;
    EXPECT_NEAR(out[0].x, 10 * std::cos(w) * std::cos(a), 1e-4) << az_deg;
    EXPECT_NEAR(out[0].z, 10 * std::sin(w), 1e-4) << az_deg;
  }
}

TEST(Decoder, StaticBoxRoomReproducesAnalyticPoints) {
  const test::BoxRoom room;
  const auto stream = test::spinVlp16([&](double a, double w) { return room.range(a, w); }, 76);
  const Decoder dec;
  std::vector<ScanPoint> out;
  for (const auto& pkt : stream.packets) ASSERT_EQ(dec.decode(pkt.data(), pkt.size(), out), DecodeStatus::Ok);
  ASSERT_EQ(out.size(), 76u * 384u);  // a closed room: every beam returns
  double worst = 0;
  for (const auto& p : out) {
    // Analytic point of the same beam: ray along the decoded direction, hit the room.
    const double a = azimuthOf(p), w = std::asin(p.z / rangeOf(p));
    double d[3];
    test::beamDirection(a, w, d);
    const double r = room.range(a, w);
    const double err = std::hypot(std::hypot(p.x - r * d[0], p.y - r * d[1]), p.z - r * d[2]);
    worst = std::max(worst, err);
    // And it lies on a wall, the floor or the ceiling.
    const double on = std::min({std::abs(p.x - room.x_max), std::abs(p.x - room.x_min), std::abs(p.y - room.y_max),
                                std::abs(p.y - room.y_min), std::abs(p.z - room.z_max), std::abs(p.z - room.z_min)});
    EXPECT_LT(on, 0.005);
  }
  EXPECT_LT(worst, 0.01);  // 1 mm range quantisation + 0.005 deg azimuth at up to 6 m
}

TEST(Decoder, DualReturnsPairsAndDuplicates) {
  std::array<FiringSequence, kVlp16SequencesPerPacket> seq{};
  for (int q = 0; q < 12; ++q) {
    seq[q].azimuth_deg = 10 + 0.4 * q;
    for (int l = 0; l < 16; ++l) {
      seq[q].strongest[l] = {5.0f, 100};
      // Even lasers see a second, farther surface; odd lasers a single one (both returns equal).
      seq[q].last[l] = l % 2 == 0 ? LaserReturn{9.0f, 20} : LaserReturn{5.0f, 100};
    }
  }
  const auto pkt = encodeVlp16Packet(seq, 0, ReturnMode::Dual);
  std::vector<ScanPoint> out;
  PacketInfo info;
  ASSERT_EQ(Decoder().decode(pkt.data(), pkt.size(), out, &info), DecodeStatus::Ok);
  EXPECT_EQ(info.mode, ReturnMode::Dual);
  // 12 sequences x 16 strongest + 12 x 8 distinct last returns; duplicates dropped as VeloView.
  ASSERT_EQ(out.size(), 12u * 16u + 12u * 8u);
  int last = 0;
  for (const auto& p : out) {
    if (p.return_index == 1) {
      ++last;
      EXPECT_NEAR(rangeOf(p), 9.0, 0.002);
    } else {
      EXPECT_NEAR(rangeOf(p), 5.0, 0.002);
    }
  }
  EXPECT_EQ(last, 96);
  // Both returns of a pair fired at the same time: block pairs share the firing schedule.
  EXPECT_FLOAT_EQ(info.block_time_s[2], info.block_time_s[3]);
  EXPECT_NEAR(info.block_time_s[2], 110.592e-6, 1e-9);

  DecoderParams p;
  p.dual_returns = DualReturns::Strongest;
  out.clear();
  ASSERT_EQ(Decoder(p).decode(pkt.data(), pkt.size(), out), DecodeStatus::Ok);
  EXPECT_EQ(out.size(), 192u);
  p.dual_returns = DualReturns::Last;
  out.clear();
  ASSERT_EQ(Decoder(p).decode(pkt.data(), pkt.size(), out), DecodeStatus::Ok);
  EXPECT_EQ(out.size(), 192u);  // every last return, duplicates included
  p.dual_returns = DualReturns::Both;
  p.drop_dual_duplicates = false;
  out.clear();
  ASSERT_EQ(Decoder(p).decode(pkt.data(), pkt.size(), out), DecodeStatus::Ok);
  EXPECT_EQ(out.size(), 384u);
}

TEST(Decoder, Hdl32PacketBuiltByHand) {
  // HDL-32E manual appendix E: 12 blocks of 32 lasers, 0xEEFF, azimuth, 3 bytes per laser.
  std::vector<uint8_t> pkt(kDataPacketSize, 0);
  for (int b = 0; b < 12; ++b) {
    uint8_t* blk = pkt.data() + 100 * b;
    blk[0] = 0xFF; blk[1] = 0xEE;
    const int az = 9000 + 16 * b;  // 0.16 deg per 46.08 us block = 10 Hz
    blk[2] = az & 0xFF; blk[3] = az >> 8;
    for (int c = 0; c < 32; ++c) {
      const int raw = 1000 + 10 * c;  // 2.0 m + 2 cm per laser
      blk[4 + 3 * c] = raw & 0xFF; blk[5 + 3 * c] = raw >> 8; blk[6 + 3 * c] = c;
    }
  }
  pkt[1204] = 0x37;
  pkt[1205] = 0x21;
  std::vector<ScanPoint> out;
  ASSERT_EQ(Decoder().decode(pkt.data(), pkt.size(), out), DecodeStatus::Ok);
  ASSERT_EQ(out.size(), 384u);
  const Calibration cal = Calibration::builtinHdl32();
  for (int b = 0; b < 12; ++b) {
    for (int c = 0; c < 32; ++c) {
      const ScanPoint& p = out[b * 32 + c];
      const double t_us = b * 46.08 + c * 1.152;
      EXPECT_NEAR(rangeOf(p), 2.0 + 0.02 * c, 1e-4);
      EXPECT_NEAR(std::asin(p.z / rangeOf(p)), cal.lasers[c].vertical_rad, 1e-5);
      EXPECT_FLOAT_EQ(p.t, static_cast<float>(t_us * 1e-6));
      EXPECT_LT(angleDiffDeg(azimuthOf(p), (90.0 + 0.16 * t_us / 46.08) * M_PI / 180), 0.01);
      EXPECT_EQ(p.ring, cal.lasers[c].ring);
    }
  }
}

TEST(Decoder, MalformedPacketsGiveStatusAndNoPoints) {
  const auto good = test::spinVlp16([](double, double) { return 5.0; }, 1).packets[0];
  const Decoder dec;
  std::vector<ScanPoint> out;
  EXPECT_EQ(dec.decode(good.data(), 1205, out), DecodeStatus::WrongSize);
  EXPECT_EQ(dec.decode(good.data(), 512, out), DecodeStatus::WrongSize);
  EXPECT_EQ(dec.decode(nullptr, 1206, out), DecodeStatus::WrongSize);
  auto bad = good;
  bad[700] = 0xDD;  // block 7 flag byte: 0xEEFF -> 0xEEDD
  EXPECT_EQ(dec.decode(bad.data(), bad.size(), out), DecodeStatus::BadBlockFlag);
  auto unknown = good;
  unknown[1205] = 0x00;  // product byte of old HDL-32E firmware
  EXPECT_EQ(dec.decode(unknown.data(), unknown.size(), out), DecodeStatus::UnknownModel);
  EXPECT_TRUE(out.empty());
  DecoderParams forced;
  forced.model = Model::VLP16;
  EXPECT_EQ(Decoder(forced).decode(unknown.data(), unknown.size(), out), DecodeStatus::Ok);
  EXPECT_EQ(out.size(), 384u);
  EXPECT_STREQ(toString(DecodeStatus::BadBlockFlag), "bad_block_flag");
}

TEST(Decoder, RangeLimitsAndZeroDistance) {
  // Ranges cycle through 0 (no return), 0.3 m, 5 m, 100 m.
  const double ranges[4] = {0.0, 0.3, 5.0, 100.0};
  int i = 0;
  const auto s = test::spinVlp16([&](double, double) { return ranges[i++ % 4]; }, 1);
  std::vector<ScanPoint> out;
  ASSERT_EQ(Decoder().decode(s.packets[0].data(), kDataPacketSize, out), DecodeStatus::Ok);
  EXPECT_EQ(out.size(), 288u);  // 3/4 of 384
  DecoderParams p;
  p.min_range_m = 1.0;
  p.max_range_m = 50.0;
  out.clear();
  ASSERT_EQ(Decoder(p).decode(s.packets[0].data(), kDataPacketSize, out), DecodeStatus::Ok);
  EXPECT_EQ(out.size(), 96u);
  for (const auto& q : out) EXPECT_NEAR(rangeOf(q), 5.0, 0.002);
}

TEST(Decoder, NoAllocationOnceCapacityIsReserved) {
  const auto s = test::spinVlp16([](double, double) { return 5.0; }, 4);
  const Decoder dec;
  std::vector<ScanPoint> out;
  out.reserve(384);
  const ScanPoint* buffer = out.data();
  for (const auto& pkt : s.packets) {
    out.clear();
    ASSERT_EQ(dec.decode(pkt.data(), pkt.size(), out), DecodeStatus::Ok);
    EXPECT_EQ(out.data(), buffer);
  }
}
