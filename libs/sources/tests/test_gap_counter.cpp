#include <gtest/gtest.h>

#include <algorithm>

#include "roadslam/sources/packet_source.h"
#include "test_packets.h"

using namespace roadslam::sources;
using roadslam::sources::test_support::makeDataPacket;

namespace {
// Real sensor counters advance by 1327 or 1328 us (1327.104 us per packet, integer clock).
uint32_t stampOf(int k, uint32_t t0) { return uint32_t(t0 + (k * 1327104LL) / 1000); }
}  // namespace

TEST(GapCounter, CountsExactlyTheRemovedPackets) {
  GapCounter gaps;
  const std::vector<int> removed = {5, 6, 7, 40, 99};
  for (int k = 0; k < 120; ++k) {
    if (std::find(removed.begin(), removed.end(), k) != removed.end()) continue;
    gaps.feed(makeDataPacket(stampOf(k, 1000), 0, k).data());
  }
  EXPECT_EQ(gaps.missing(), removed.size());
}

TEST(GapCounter, HandlesTheTopOfTheHourWrap) {
  GapCounter gaps;
  const uint32_t t0 = 3600u * 1000000u - 5000u;  // 5 ms before the wrap
  for (int k = 0; k < 10; ++k) {
    if (k == 6) continue;
    gaps.feed(makeDataPacket(stampOf(k, t0) % 3600000000u, 0, k).data());
  }
  EXPECT_EQ(gaps.missing(), 1u);
}

TEST(GapCounter, DualReturnHalvesThePeriod) {
  GapCounter gaps;
  for (int k = 0; k < 20; ++k) {
    if (k == 3) continue;
    gaps.feed(makeDataPacket(uint32_t(k * 663552LL / 1000), 0, k, 0x39).data());
  }
  EXPECT_EQ(gaps.missing(), 1u);
}

TEST(Classify, ByPortAndSize) {
  PortConfig ports;
  EXPECT_EQ(classify(ports, 2368, 1206), PacketKind::Data);
  EXPECT_EQ(classify(ports, 2368, 1205), PacketKind::Malformed);
  EXPECT_EQ(classify(ports, 8308, 512), PacketKind::Position);
  EXPECT_EQ(classify(ports, 8308, 1206), PacketKind::Malformed);
  EXPECT_EQ(classify(ports, 53, 1206), PacketKind::Other);
}

TEST(GapCounter, Hdl32PeriodFromTheProductByteOrAForcedModel) {
  // HDL-32E: 12 blocks x 46.08 us = 552.96 us per packet (manual 63-9113, appendix E).
  GapCounter by_byte;
  for (int k = 0; k < 50; ++k)
    if (k != 20) by_byte.feed(makeDataPacket(uint32_t(k * 552960LL / 1000), 0, k, 0x37, 0x21).data());
  EXPECT_EQ(by_byte.missing(), 1u);
  // An early VLP-16 reporting 0x21: forced to HDL-32E, every step looks like a gap; forced to VLP-16
  // or left to the packets' layout (10 Hz: 0.4 deg per 110.592 us block; channels k and k+16 the
  // same laser), none is missing, and a real gap still counts.
  GapCounter as_hdl32(0, roadslam::velodyne::Model::HDL32), forced(0, roadslam::velodyne::Model::VLP16), by_layout;
  for (int k = 0; k < 150; ++k) {
    if (k == 120) continue;
    auto p = makeDataPacket(stampOf(k, 1000), uint16_t(k * 480 % 36000), k, 0x37, 0x21);
    for (int b = 0; b < 12; ++b) std::copy_n(p.begin() + b * 100 + 4, 48, p.begin() + b * 100 + 52);
    as_hdl32.feed(p.data());
    forced.feed(p.data());
    by_layout.feed(p.data());
    if (k == 50) {
      EXPECT_EQ(by_layout.missing(), 0u) << "while the layout window is open";
    }
  }
  EXPECT_GT(as_hdl32.missing(), 140u);
  EXPECT_EQ(forced.missing(), 1u);
  EXPECT_EQ(by_layout.missing(), 1u);
}
