// The layout check (layout.h) and the model rule (model_choice.h) on encoder-made streams whose
// layout is known: VLP-16 and HDL-32E firing timing, each with its own product byte and the other's.
#include <gtest/gtest.h>

#include <cmath>

#include "roadslam/velodyne/layout.h"
#include "roadslam/velodyne/model_choice.h"
#include "roadslam/velodyne/sweep_assembler.h"
#include "synthetic.h"

using namespace roadslam;
using namespace roadslam::velodyne;

namespace {

// A road seen from 1.9 m: the range of a beam depends on its elevation, so two different lasers
// of one block (HDL-32E channels k and k+16) see different ranges; beams at or above the horizon
// see a wall 30 m away.
double road(double, double w) { return w < -0.02 ? std::min(1.9 / std::sin(-w), 60.0) : 30.0; }

LayoutVerdict verdictOf(const test::SyntheticStream& s, std::size_t step = 1) {
  LayoutDetector d;
  for (std::size_t i = 0; i < s.packets.size(); i += step) d.add(s.packets[i].data(), s.packets[i].size());
  return d.verdict();
}

/// Rewrites each packet's timestamp as if the sensor's clock ran \p scale times as fast.
void scaleClock(test::SyntheticStream& s, double scale) {
  for (auto& p : s.packets) {
    const uint32_t t = p[kTimestampOffset] | p[kTimestampOffset + 1] << 8 | p[kTimestampOffset + 2] << 16 |
                       uint32_t(p[kTimestampOffset + 3]) << 24;
    const auto u = static_cast<uint32_t>(std::lround(t * scale));
    for (int i = 0; i < 4; ++i) p[kTimestampOffset + i] = static_cast<uint8_t>(u >> (8 * i));
  }
}

}  // namespace

TEST(Layout, Vlp16StreamHasTheVlp16BlockPeriod) {
  const auto s = test::spinVlp16(road, 150);
  const LayoutVerdict v = verdictOf(s);
  EXPECT_EQ(v.model, Model::VLP16);
  EXPECT_NEAR(v.block_period_us, 110.592, 0.5);  // 2 x 55.296 us (VLP-16 manual 9.5)
  EXPECT_EQ(v.packets, LayoutDetector::kWindowPackets);  // the window, not the whole stream
  EXPECT_EQ(v.rate_samples, LayoutDetector::kWindowPackets - 1);
  EXPECT_GT(v.channel_agreement, 0.99);  // channels k and k+16: the same laser
  EXPECT_EQ(v.product_byte, 0x22);
  EXPECT_EQ(v.describe(), "VLP-16 layout (110.6 us per block)");
}

TEST(Layout, Hdl32StreamHasTheHdl32BlockPeriod) {
  const auto s = test::spinHdl32(road, 150);
  const LayoutVerdict v = verdictOf(s);
  EXPECT_EQ(v.model, Model::HDL32);
  EXPECT_NEAR(v.block_period_us, 46.08, 0.5);  // HDL-32E manual appendix E
  EXPECT_LT(v.channel_agreement, 0.45);
  EXPECT_EQ(v.product_byte, 0x21);
}

TEST(Layout, RateAndDroppedPacketsDoNotMatter) {
  for (const double hz : {5.0, 10.0, 20.0}) {
    const auto vlp = test::spinVlp16(road, 400, hz);
    const LayoutVerdict v = verdictOf(vlp, 3);  // two of every three packets lost
    EXPECT_EQ(v.model, Model::VLP16) << hz;
    EXPECT_NEAR(v.block_period_us, 110.592, 1.0) << hz;
    EXPECT_EQ(verdictOf(test::spinHdl32(road, 400, hz), 3).model, Model::HDL32) << hz;
  }
}

TEST(Layout, DualReturnVlp16) {
  const auto s = test::spinVlp16(road, 150, 10.0, 0.0, 1000000, ReturnMode::Dual);
  EXPECT_EQ(verdictOf(s).model, Model::VLP16);
}

TEST(Layout, ABlockPeriodOfNeitherModelIsInconclusive) {
  auto s = test::spinVlp16(road, 150);
  scaleClock(s, 0.7);  // 77 us per block: another sensor (or a broken clock)
  const LayoutVerdict v = verdictOf(s);
  EXPECT_EQ(v.model, Model::Unknown);
  EXPECT_NEAR(v.block_period_us, 0.7 * 110.592, 1.0);
  EXPECT_EQ(v.describe().rfind("layout inconclusive (77.", 0), 0u) << v.describe();
  // auto: the product byte decides, without a warning
  const ModelChoice c = chooseModel(Model::Unknown, v);
  EXPECT_EQ(c.model, Model::VLP16);
  EXPECT_EQ(c.source, ModelSource::ProductByte);
  EXPECT_EQ(c.warning, "");
}

TEST(Layout, ChannelsContradictingTheRateAreInconclusive) {
  auto s = test::spinHdl32(road, 150);
  scaleClock(s, 110.592 / 46.08);  // VLP-16 timing, HDL-32E channels
  const LayoutVerdict v = verdictOf(s);
  EXPECT_NEAR(v.block_period_us, 110.592, 1.0);
  EXPECT_EQ(v.model, Model::Unknown);
}

TEST(Layout, OnePacketIsJudgedByItsChannelsWhenTheyAgree) {
  const auto vlp = test::spinVlp16(road, 1);
  const LayoutVerdict v = verdictOf(vlp);
  EXPECT_EQ(v.rate_samples, 0u);
  EXPECT_EQ(v.model, Model::VLP16);
  EXPECT_EQ(v.describe().rfind("VLP-16 layout (channels k and k+16 agree in 100 % of", 0), 0u) << v.describe();
  // Pairs that disagree alone prove nothing (random bytes disagree too): inconclusive.
  EXPECT_EQ(verdictOf(test::spinHdl32(road, 1)).model, Model::Unknown);
}

TEST(Layout, NotDataPacketsAreIgnored) {
  LayoutDetector d;
  const uint8_t junk[kDataPacketSize] = {};  // no 0xEEFF block flags
  d.add(junk, sizeof junk);
  d.add(junk, 512);
  const LayoutVerdict v = d.verdict();
  EXPECT_EQ(v.packets, 0u);
  EXPECT_EQ(v.describe(), "no data packets");
  EXPECT_EQ(chooseModel(Model::Unknown, v).model, Model::Unknown);
  EXPECT_EQ(chooseModel(Model::Unknown, v).warning, "");
}

TEST(ModelChoice, MatchingByteDecidesSilently) {
  const ModelChoice c = chooseModel(Model::Unknown, verdictOf(test::spinHdl32(road, 120)));
  EXPECT_EQ(c.model, Model::HDL32);
  EXPECT_EQ(c.source, ModelSource::ProductByte);
  EXPECT_EQ(c.warning, "");
}

TEST(ModelChoice, Vlp16LayoutWithTheHdl32ByteDecodesAsVlp16WithAWarning) {
  const auto s = test::spinVlp16(road, 120, 10.0, 0.0, 1000000, ReturnMode::Strongest, Model::HDL32);
  const ModelChoice c = chooseModel(Model::Unknown, verdictOf(s));
  EXPECT_EQ(c.model, Model::VLP16);
  EXPECT_EQ(c.source, ModelSource::PacketLayout);
  EXPECT_STREQ(toString(c.source), "packet layout");
  EXPECT_EQ(c.warning,
            "packets have the VLP-16 layout (110.6 us per block) but product byte 0x21 says HDL-32E; decoding as "
            "VLP-16; set [velodyne] model = hdl32 to force");
  const std::string cli = chooseModel(Model::Unknown, verdictOf(s), "--model").warning;
  EXPECT_EQ(cli.substr(cli.find("; decoding")), "; decoding as VLP-16; set --model hdl32 to force");
}

TEST(ModelChoice, Hdl32LayoutWithTheVlp16ByteDecodesAsHdl32WithAWarning) {
  const auto s = test::spinHdl32(road, 120, 10.0, 0.0, 1000000, Model::VLP16);
  const ModelChoice c = chooseModel(Model::Unknown, verdictOf(s));
  EXPECT_EQ(c.model, Model::HDL32);
  EXPECT_EQ(c.source, ModelSource::PacketLayout);
  EXPECT_EQ(c.warning,
            "packets have the HDL-32E layout (46.1 us per block) but product byte 0x22 says VLP-16; decoding as "
            "HDL-32E; set [velodyne] model = vlp16 to force");
}

TEST(ModelChoice, ASetModelIsObeyedAndADisagreeingLayoutWarned) {
  const LayoutVerdict vlp = verdictOf(test::spinVlp16(road, 120));
  const ModelChoice c = chooseModel(Model::HDL32, vlp);
  EXPECT_EQ(c.model, Model::HDL32);
  EXPECT_EQ(c.source, ModelSource::Ini);
  EXPECT_EQ(c.warning,
            "packets have the VLP-16 layout (110.6 us per block) but [velodyne] model = hdl32 forces HDL-32E; "
            "decoding as HDL-32E as set");
  const ModelChoice same = chooseModel(Model::VLP16, vlp);
  EXPECT_EQ(same.model, Model::VLP16);
  EXPECT_EQ(same.source, ModelSource::Ini);
  EXPECT_EQ(same.warning, "");
}

TEST(ModelChoice, AnUnknownProductByteIsNotDecoded) {
  auto s = test::spinVlp16(road, 120);
  for (auto& p : s.packets) p[kProductIdOffset] = 0x28;  // VLP-32C
  const ModelChoice c = chooseModel(Model::Unknown, verdictOf(s));
  EXPECT_EQ(c.model, Model::Unknown);
  EXPECT_EQ(c.warning,
            "product byte 0x28 is neither VLP-16 (0x22) nor HDL-32E (0x21): the data packets are not decoded; they "
            "have the VLP-16 layout (110.6 us per block): set [velodyne] model = vlp16 to decode them");
}

// The stream model reaches the decoder: an HDL-32E stream with the VLP-16 byte decoded by its layout
// gives the room it saw; decoded by its byte, the lasers' elevations are another sensor's.
TEST(ModelChoice, StreamModelDecodesTheLayoutNotTheByte) {
  const test::BoxRoom room;
  const auto s = test::spinHdl32([&](double a, double w) { return room.range(a, w); }, 200, 10.0, 0.0, 1000000,
                                 Model::VLP16);
  auto insideFraction = [&](Model stream_model) {
    SweepAssembler a;
    a.setStreamModel(stream_model);
    std::size_t inside = 0, all = 0;
    auto count = [&](const Scan& sw) {
      for (const auto& p : sw.points) {
        ++all;
        inside += std::abs(p.x) < room.x_max + 0.05 && std::abs(p.y) < room.y_max + 0.05 &&
                  p.z > room.z_min - 0.05 && p.z < room.z_max + 0.05;
      }
    };
    for (std::size_t i = 0; i < s.packets.size(); ++i) {
      a.addPacket(s.packets[i].data(), s.packets[i].size(), s.stamps_s[i]);
      while (a.hasSweep()) count(a.takeSweep());
    }
    a.finish();
    while (a.hasSweep()) count(a.takeSweep());
    EXPECT_EQ(all, s.packets.size() * 12 * 32);
    return static_cast<double>(inside) / static_cast<double>(all);
  };
  const double as_layout = insideFraction(Model::HDL32), as_byte = insideFraction(Model::Unknown);
  EXPECT_GT(as_layout, 0.999);
  EXPECT_LT(as_byte, 0.9);
}
