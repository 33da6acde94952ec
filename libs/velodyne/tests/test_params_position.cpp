// DecoderParams ini round trip and errors; $GPRMC parsing; position packet round trip.
#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>

#include "roadslam/velodyne/decoder_params.h"
#include "roadslam/velodyne/encoder.h"
#include "roadslam/velodyne/position.h"

using namespace roadslam::velodyne;

TEST(DecoderParams, SaveLoadRoundTrip) {
  DecoderParams a;
  a.model = Model::HDL32;
  a.calibration_file = "/tmp/x.xml";
  a.min_range_m = 0.9;
  a.max_range_m = 80;
  a.dual_returns = DualReturns::Last;
  a.drop_dual_duplicates = false;
  a.intra_block_azimuth = false;
  a.cut_azimuth_rad = M_PI / 2;
  a.stamp_source = StampSource::Sensor;
  mrpt::config::CConfigFileMemory cfg;
  a.saveToConfigFile(cfg, "velodyne");
  EXPECT_DOUBLE_EQ(std::stod(cfg.read_string("velodyne", "cut_azimuth_deg", "")), 90.0);  // degrees on disk
  DecoderParams b;
  b.loadFromConfigFile(cfg, "velodyne");
  EXPECT_EQ(b.model, a.model);
  EXPECT_EQ(b.calibration_file, a.calibration_file);
  EXPECT_DOUBLE_EQ(b.min_range_m, a.min_range_m);
  EXPECT_DOUBLE_EQ(b.max_range_m, a.max_range_m);
  EXPECT_EQ(b.dual_returns, a.dual_returns);
  EXPECT_EQ(b.drop_dual_duplicates, a.drop_dual_duplicates);
  EXPECT_EQ(b.intra_block_azimuth, a.intra_block_azimuth);
  EXPECT_NEAR(b.cut_azimuth_rad, a.cut_azimuth_rad, 1e-12);
  EXPECT_EQ(b.stamp_source, a.stamp_source);
}

TEST(DecoderParams, BadValuesNameTheKey) {
  for (const auto& [key, value] : std::vector<std::pair<std::string, std::string>>{
           {"model", "hdl64"}, {"dual_returns", "first"}, {"stamp_source", "gps"}, {"min_range_m", "near"}}) {
    mrpt::config::CConfigFileMemory cfg;
    cfg.write("velodyne", key, value);
    DecoderParams p;
    try {
      p.loadFromConfigFile(cfg, "velodyne");
      FAIL() << "no exception for " << key << "=" << value;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

TEST(PositionPacket, EncodeDecodeRoundTrip) {
  const char* nmea = "$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2E";
  const auto pkt = encodePositionPacket(123456, nmea);
  PositionPacket pp;
  ASSERT_TRUE(decodePositionPacket(pkt.data(), pkt.size(), pp));
  EXPECT_EQ(pp.timestamp_us, 123456u);
  EXPECT_EQ(pp.nmea, nmea);
  ASSERT_TRUE(pp.fix);
  EXPECT_TRUE(pp.fix->valid());
  EXPECT_NEAR(pp.fix->position.lat_deg, 36.829130930, 1e-9);
  EXPECT_FALSE(decodePositionPacket(pkt.data(), 511, pp));
  const auto empty = encodePositionPacket(1, "");
  ASSERT_TRUE(decodePositionPacket(empty.data(), empty.size(), pp));
  EXPECT_FALSE(pp.fix);
}
