// Sweep cutting on a synthetic spinning VLP-16 whose azimuth/time truth is known.
#include <gtest/gtest.h>

#include <cmath>

#include "roadslam/velodyne/sweep_assembler.h"
#include "synthetic.h"

using namespace roadslam;
using namespace roadslam::velodyne;

namespace {

std::vector<Scan> assemble(const test::SyntheticStream& s, const DecoderParams& p, SweepStats* st = nullptr) {
  SweepAssembler a(p);
  std::vector<Scan> out;
  for (std::size_t i = 0; i < s.packets.size(); ++i) {
    a.addPacket(s.packets[i].data(), s.packets[i].size(), s.stamps_s[i]);
    while (a.hasSweep()) out.push_back(a.takeSweep());
  }
  a.finish();
  while (a.hasSweep()) out.push_back(a.takeSweep());
  if (st) *st = a.stats();
  return out;
}

double azimuthDeg(const ScanPoint& p) {
  double a = std::atan2(-p.y, p.x) * 180 / M_PI;
  return a < 0 ? a + 360 : a;
}

}  // namespace

TEST(SweepAssembler, CutsAtZeroAzimuthWithPartialEnds) {
  // 10 Hz, starting at 100 deg: 0.1 s per turn = 75.36 packets; 300 packets = 3.98 turns.
  const auto s = test::spinVlp16([](double, double) { return 5.0; }, 300, 10.0, 100.0);
  SweepStats st;
  const auto sweeps = assemble(s, DecoderParams{}, &st);
  ASSERT_EQ(sweeps.size(), 5u);  // 260 deg partial, 3 full turns, partial rest
  EXPECT_TRUE(sweeps.front().partial);
  EXPECT_TRUE(sweeps.back().partial);
  for (int i = 1; i < 4; ++i) {
    const Scan& sw = sweeps[i];
    EXPECT_FALSE(sw.partial);
    EXPECT_TRUE(sw.has_point_times);
    EXPECT_TRUE(sw.has_rings);
    // A full turn: about 0.1 s / 110.592 us blocks x 32 points.
    EXPECT_NEAR(static_cast<double>(sw.points.size()), 0.1 / 110.592e-6 * 32, 64);
    EXPECT_LT(azimuthDeg(sw.points.front()), 0.5);   // starts right after 0 deg
    // Ends at the turn: the cut is per block (VeloView), so the last lasers of the block before
    // the wrap may lie up to one block advance (0.4 deg) past 360.
    const double end = azimuthDeg(sw.points.back());
    EXPECT_TRUE(end > 359.5 || end < 0.4) << end;
    EXPECT_FLOAT_EQ(sw.points.front().t, 0.0f);
    float prev = -1;
    for (const auto& p : sw.points) {
      EXPECT_GE(p.t, prev);  // firing order is time order
      prev = p.t;
    }
    EXPECT_NEAR(prev, 0.1, 0.0002);
    // Consecutive sweep stamps one revolution apart (capture clock of the synthetic stream).
    EXPECT_NEAR(sw.stamp_s - sweeps[i - 1].stamp_s, i == 1 ? 260.0 / 3600 : 0.1, 2e-4);
  }
  EXPECT_EQ(st.packets, 300u);
  EXPECT_EQ(st.sweeps, 5u);
  EXPECT_EQ(st.partial_sweeps, 2u);
  EXPECT_EQ(st.points, 300u * 384u);
}

TEST(SweepAssembler, ConfigurableCutAngle) {
  const auto s = test::spinVlp16([](double, double) { return 5.0; }, 300, 10.0, 100.0);
  DecoderParams p;
  p.cut_azimuth_rad = 90.0 * M_PI / 180;
  const auto sweeps = assemble(s, p);
  ASSERT_GE(sweeps.size(), 4u);
  for (std::size_t i = 1; i + 1 < sweeps.size(); ++i) {
    EXPECT_NEAR(azimuthDeg(sweeps[i].points.front()), 90.0, 0.5);
    EXPECT_NEAR(azimuthDeg(sweeps[i].points.back()), 90.0, 0.5);
  }
}

TEST(SweepAssembler, SensorClockUnwrapsTheHour) {
  // Timestamps start 0.15 s before the top of the hour: the sensor clock wraps to 0 mid-stream.
  const uint32_t t0 = 3600u * 1000000u - 150000u;
  const auto s = test::spinVlp16([](double, double) { return 5.0; }, 300, 10.0, 0.0, t0);
  DecoderParams p;
  p.stamp_source = StampSource::Sensor;
  const auto sweeps = assemble(s, p);
  ASSERT_GE(sweeps.size(), 4u);
  for (std::size_t i = 1; i < sweeps.size(); ++i)
    EXPECT_NEAR(sweeps[i].stamp_s - sweeps[i - 1].stamp_s, 0.1, 2e-4) << i;
  EXPECT_NEAR(sweeps[0].stamp_s, t0 * 1e-6, 1e-6);
}

TEST(SweepAssembler, BadPacketsAreCountedNotFatal) {
  auto s = test::spinVlp16([](double, double) { return 5.0; }, 100);
  s.packets[10][0] = 0;  // corrupt a block flag
  SweepAssembler a;
  for (std::size_t i = 0; i < s.packets.size(); ++i) a.addPacket(s.packets[i].data(), s.packets[i].size(), s.stamps_s[i]);
  const uint8_t short_pkt[10] = {};
  EXPECT_EQ(a.addPacket(short_pkt, sizeof short_pkt, 0), DecodeStatus::WrongSize);
  EXPECT_EQ(a.stats().packets, 101u);
  EXPECT_EQ(a.stats().malformed(), 2u);
  EXPECT_EQ(a.stats().status[static_cast<int>(DecodeStatus::BadBlockFlag)], 1u);
  EXPECT_EQ(a.stats().status[static_cast<int>(DecodeStatus::WrongSize)], 1u);
}

TEST(SweepAssembler, EmptyRevolutionsAreDropped) {
  // No returns at all (open sky everywhere) gives no sweep, as VeloView's IgnoreEmptyFrames.
  const auto s = test::spinVlp16([](double, double) { return 0.0; }, 200);
  SweepStats st;
  EXPECT_TRUE(assemble(s, DecoderParams{}, &st).empty());
  EXPECT_GE(st.empty_sweeps_dropped, 2u);
}

TEST(SweepAssembler, ReportsTheCutBlockAndTakesRawPackets) {
  // 10 Hz from 359.5 deg: 0.4 deg per block, so the first wrap falls inside the first packet.
  const auto s = test::spinVlp16([](double, double) { return 5.0; }, 80, 10.0, 359.5);
  SweepAssembler a;
  std::vector<int> cuts;
  for (std::size_t i = 0; i < s.packets.size(); ++i) {
    RawPacket raw;
    raw.stamp_s = s.stamps_s[i];
    raw.dst_port = kDefaultDataPort;
    raw.payload.assign(s.packets[i].begin(), s.packets[i].end());
    ASSERT_EQ(a.addPacket(raw), DecodeStatus::Ok);
    if (a.lastCutBlock() >= 0) cuts.push_back(static_cast<int>(i) * 100 + a.lastCutBlock());
  }
  // Block k of packet i starts at 359.5 + 0.39813 * (12 i + k) deg (2 x 55.296 us at 3600 deg/s):
  // 360 is first reached at 12 i + k >= 0.5 / 0.39813 -> block 2 of packet 0, and 720 at
  // 12 i + k >= 360.5 / 0.39813 = 905.5 -> 906 = packet 75, block 6.
  ASSERT_EQ(cuts.size(), 2u);
  EXPECT_EQ(cuts[0], 2);
  EXPECT_EQ(cuts[1], 75 * 100 + 6);
}
