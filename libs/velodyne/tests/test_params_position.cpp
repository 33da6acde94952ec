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

TEST(Nmea, ParsesGprmcFields) {
  GpsFix f;
  ASSERT_TRUE(parseRmc("$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2E", f));
  EXPECT_TRUE(f.valid);
  EXPECT_NEAR(f.latitude_deg, 36.829130930, 1e-9);
  EXPECT_NEAR(f.longitude_deg, -2.407571547, 1e-9);
  EXPECT_NEAR(f.speed_mps, 0.034 * 0.514444, 1e-5);
  EXPECT_NEAR(f.course_rad, 212.5 * M_PI / 180, 1e-12);
  EXPECT_NEAR(f.time_of_day_s, 8 * 3600 + 18 * 60 + 2, 1e-9);
  EXPECT_EQ(f.year, 2016);
  EXPECT_NEAR(f.epochSeconds(), 1453364282.0, 1e-6);  // date -u -d '2016-01-21 08:18:02' +%s
}

TEST(Nmea, RejectsBadChecksumAndOtherSentences) {
  GpsFix f;
  EXPECT_FALSE(parseRmc("$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2F", f));
  EXPECT_FALSE(parseRmc("$GPGGA,081802.00,3649.7,N,00224.4,W,1,08,0.9,545.4,M,46.9,M,,*47", f));
  EXPECT_FALSE(parseRmc("", f));
  EXPECT_FALSE(parseRmc("$GPRMC,,,,", f));
  EXPECT_FALSE(parseRmc("$GPRMC,081802,A,3699.0,N,00224.4,W,0,0,210116,,", f));  // 99 minutes
  ASSERT_TRUE(parseRmc("$GPRMC,220632,V,3707.83,S,12139.29,E,0.0,0.0,111212,,", f));
  EXPECT_FALSE(f.valid);
  EXPECT_LT(f.latitude_deg, 0);
  EXPECT_GT(f.longitude_deg, 0);
}

TEST(PositionPacket, EncodeDecodeRoundTrip) {
  const char* nmea = "$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2E";
  const auto pkt = encodePositionPacket(123456, nmea);
  PositionPacket pp;
  ASSERT_TRUE(decodePositionPacket(pkt.data(), pkt.size(), pp));
  EXPECT_EQ(pp.timestamp_us, 123456u);
  EXPECT_EQ(pp.nmea, nmea);
  EXPECT_TRUE(pp.has_fix);
  EXPECT_TRUE(pp.fix.valid);
  EXPECT_FALSE(decodePositionPacket(pkt.data(), 511, pp));
  const auto empty = encodePositionPacket(1, "");
  ASSERT_TRUE(decodePositionPacket(empty.data(), empty.size(), pp));
  EXPECT_FALSE(pp.has_fix);
}
