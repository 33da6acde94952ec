// Encoder output checked byte by byte against the VLP-16 manual's packet layout (section 9.3).
#include <gtest/gtest.h>

#include <cstring>

#include "roadslam/velodyne/encoder.h"

using namespace roadslam::velodyne;

namespace {
uint16_t le16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
}  // namespace

TEST(EncoderLayout, StrongestPacketBytesFollowTheManual) {
  std::array<FiringSequence, kVlp16SequencesPerPacket> seq{};
  for (int s = 0; s < kVlp16SequencesPerPacket; ++s) {
    seq[s].azimuth_deg = 359.9 + 0.2 * s;  // wraps past 360 after the first sequence
    for (int l = 0; l < kVlp16Lasers; ++l)
      seq[s].strongest[l] = {static_cast<float>(1.0 + 0.01 * l + s), static_cast<uint8_t>(l + s)};
  }
  seq[3].strongest[5].range_m = 0;      // no return
  seq[3].strongest[6].range_m = 200.f;  // beyond the 131 m field
  const auto pkt = encodeVlp16Packet(seq, 123456789u, ReturnMode::Strongest, Model::VLP16);
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    const uint8_t* blk = pkt.data() + 100 * b;
    EXPECT_EQ(le16(blk), 0xEEFF);
    const int expected_az = (35990 + 40 * b) % 36000;
    EXPECT_EQ(le16(blk + 2), expected_az) << b;
    // Channel 16 + l of block b is laser l of sequence 2b + 1.
    const uint8_t* ch = blk + 4 + 3 * (16 + 2);
    EXPECT_EQ(le16(ch), static_cast<uint16_t>((1.02 + 2 * b + 1) / 0.002 + 0.5));
    EXPECT_EQ(ch[2], 2 + 2 * b + 1);
  }
  const uint8_t* blk1 = pkt.data() + 100;
  EXPECT_EQ(le16(blk1 + 4 + 3 * (16 + 5)), 0);
  EXPECT_EQ(le16(blk1 + 4 + 3 * (16 + 6)), 0);
  uint32_t ts = 0;
  for (int i = 0; i < 4; ++i) ts |= uint32_t{pkt[1200 + i]} << (8 * i);
  EXPECT_EQ(ts, 123456789u);
  EXPECT_EQ(pkt[1204], 0x37);
  EXPECT_EQ(pkt[1205], 0x22);
}

TEST(EncoderLayout, DualBlocksPairShareAzimuth) {
  std::array<FiringSequence, kVlp16SequencesPerPacket> seq{};
  for (int s = 0; s < kVlp16SequencesPerPacket; ++s) {
    seq[s].azimuth_deg = 10.0 + 0.2 * s;
    seq[s].strongest[0] = {5.0f, 1};
    seq[s].last[0] = {7.0f, 2};
  }
  const auto pkt = encodeVlp16Packet(seq, 0, ReturnMode::Dual, Model::VLP16);
  for (int j = 0; j < 6; ++j) {
    const uint8_t* a = pkt.data() + 100 * (2 * j);
    const uint8_t* b = a + 100;
    EXPECT_EQ(le16(a + 2), le16(b + 2));
    EXPECT_EQ(le16(a + 2), 1000 + 40 * j);
    EXPECT_EQ(le16(a + 4), 3500);  // last 7 m first
    EXPECT_EQ(le16(b + 4), 2500);  // then strongest 5 m
  }
  EXPECT_EQ(pkt[1204], 0x39);
}

TEST(EncoderLayout, PositionPacketCarriesStampAndNmea) {
  const char* nmea = "$GPRMC,081802,A,3649.748,N,00224.454,W,000.0,000.0,210116,,*1A";
  const auto pkt = encodePositionPacket(42u, nmea);
  EXPECT_EQ(pkt[198], 42);
  EXPECT_EQ(std::memcmp(pkt.data() + 206, nmea, std::strlen(nmea)), 0);
  EXPECT_EQ(pkt[206 + std::strlen(nmea)], 0);
}
