// NMEA 0183 parsing: sentences built by hand from the standard's field lists (checksums computed here
// independently of the encoder), the encoder's output parsed back, and every kind of bad input
// counted and named rather than thrown.
#include <gtest/gtest.h>

#include <cstdio>

#include "roadslam/gnss/nmea.h"

using namespace roadslam::gnss;

namespace {
std::string withChecksum(const std::string& body) {
  unsigned sum = 0;
  for (char c : body) sum ^= static_cast<unsigned char>(c);
  char b[8];
  std::snprintf(b, sizeof(b), "*%02X", sum);
  return "$" + body + b;
}
}  // namespace

TEST(Nmea, KnownSentence) {
  // the classic example from the NMEA reference (gpsd's NMEA revealed): checksum 47
  NmeaParser p;
  EXPECT_FALSE(p.feed("$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n", 100.0));
  const auto f = p.flush();
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->valid());
  EXPECT_NEAR(f->position.lat_deg, 48 + 7.038 / 60, 1e-12);
  EXPECT_NEAR(f->position.lon_deg, 11 + 31.0 / 60, 1e-12);
  EXPECT_NEAR(f->position.h_m, 545.4 + 46.9, 1e-9);
  EXPECT_EQ(f->satellites, 8);
  EXPECT_DOUBLE_EQ(f->hdop, 0.9);
  EXPECT_DOUBLE_EQ(f->time_of_day_s, 12 * 3600 + 35 * 60 + 19);
  EXPECT_DOUBLE_EQ(f->t_receive_s, 100.0);
  EXPECT_TRUE(std::isnan(f->t_receiver_s));  // no RMC date yet
  EXPECT_EQ(p.counters().bad_checksum, 0u);
}

TEST(Nmea, EpochGroupsGgaRmcVtgGst) {
  const std::string log =
      "1700000000.05 " + withChecksum("GNRMC,221320.00,A,4808.2200,N,01134.5000,E,48.6,90.0,141123,,,A") + "\n" +
      "1700000000.06 " + withChecksum("GNGGA,221320.00,4808.2200,N,01134.5000,E,4,12,0.8,500.0,M,47.0,M,,") + "\n" +
      "1700000000.07 " + withChecksum("GNVTG,90.0,T,,M,48.6,N,90.0,K,A") + "\n" +
      "1700000000.08 " + withChecksum("GNGST,221320.00,0.5,0.6,0.4,10.0,0.03,0.02,0.05") + "\n" +
      "1700000001.05 " + withChecksum("GNGGA,221321.00,4808.2300,S,01134.5000,W,1,12,1.2,500.0,M,47.0,M,,") + "\n";
  const NmeaLog l = parseNmeaLog(log);
  ASSERT_EQ(l.fixes.size(), 2u);
  const GnssFix& a = l.fixes[0];
  EXPECT_EQ(a.sentences, "RMC,GGA,VTG,GST");
  EXPECT_EQ(a.quality, 4);
  // 14 Nov 2023 22:13:20 UTC = 1700000000 s
  EXPECT_DOUBLE_EQ(a.t_receiver_s, 1700000000.0);
  EXPECT_DOUBLE_EQ(a.t_receive_s, 1700000000.05);
  EXPECT_NEAR(a.speed_mps, 25.0, 1e-9);  // VTG's km/h wins over RMC's knots
  EXPECT_NEAR(a.course_rad, M_PI / 2, 1e-12);
  const Eigen::Matrix3d C = a.covarianceEnu(5.0, 10.0);
  EXPECT_NEAR(C(0, 0), 0.02 * 0.02, 1e-12);  // east = sigma longitude
  EXPECT_NEAR(C(1, 1), 0.03 * 0.03, 1e-12);
  EXPECT_NEAR(C(2, 2), 0.05 * 0.05, 1e-12);
  const GnssFix& b = l.fixes[1];
  EXPECT_LT(b.position.lat_deg, 0);
  EXPECT_LT(b.position.lon_deg, 0);
  EXPECT_DOUBLE_EQ(b.t_receiver_s, 1700000001.0);
  EXPECT_NEAR(b.covarianceEnu(5.0, 10.0)(0, 0), 36.0, 1e-9);  // HDOP 1.2 x 5 m
}

TEST(Nmea, BadInputIsCountedAndNamedNeverFatal) {
  const std::string good1 = withChecksum("GPRMC,000001.00,A,4808.0000,N,01134.0000,E,0.0,0.0,010124,,,A");
  std::string corrupt = withChecksum("GPGGA,000002.00,4808.0000,N,01134.0000,E,1,08,0.9,500.0,M,0.0,M,,");
  corrupt[20] = '9';
  const std::string log = good1 + "\n" + corrupt + "\n" +
                          "$GPGGA,no checksum at all\n" +
                          withChecksum("GPGGA,000003.00,,,,,0,00,99.9,,M,,M,,") + "\n" +      // no fix
                          withChecksum("GPGGA,000002.50,4808.0,N,01134.0,E,1,08,0.9,0,M,0,M,,") + "\n" +  // back in time
                          withChecksum("GPGGA,000010.00,4808.0,N,01134.0,E,1,08,0.9,0,M,0,M,,") + "\n" +  // 7 s jump
                          withChecksum("GPDTM,999,,0.0,N,0.0,E,0.0,999") + "\n" +
                          withChecksum("GPGGA,000011.00,4808.0,N,01134.0,E,1,08,0.9,0,M,0,M,,") + "\n" +  // other datum
                          withChecksum("GPDTM,W84,,0.0,N,0.0,E,0.0,W84") + "\n" +
                          withChecksum("GPGGA,000012.00,48X8.0,N,01134.0,E,1,08,0.9,0,M,0,M,,") + "\n" +  // malformed
                          withChecksum("GPGSV,1,1,00") + "\n" +
                          withChecksum("GPGGA,000013.00,4808.0,N,01134.0,E,1,08,0.9,0,M,0,M,,") + "\n";
  const NmeaLog l = parseNmeaLog(log);
  const auto n = l.counters.named();
  EXPECT_EQ(n.at("bad checksum"), 2u);
  EXPECT_EQ(n.at("no fix"), 2u);  // the quality-0 epoch and the malformed one
  EXPECT_EQ(n.at("time backwards"), 1u);
  EXPECT_EQ(n.at("time jump"), 1u);
  EXPECT_EQ(n.at("other datum"), 1u);
  EXPECT_EQ(n.at("malformed"), 1u);
  EXPECT_EQ(n.at("unsupported sentence"), 1u);
  // kept: the first RMC, the 7 s jump's fix and the last one
  ASSERT_EQ(l.fixes.size(), 3u);
  EXPECT_DOUBLE_EQ(l.fixes[1].time_of_day_s, 10.0);
  EXPECT_DOUBLE_EQ(l.fixes[2].time_of_day_s, 13.0);
  EXPECT_FALSE(l.problems.empty());
  EXPECT_NE(l.problems[0].find("line 2"), std::string::npos);
}

TEST(Nmea, EncoderRoundTrip) {
  GnssFix f;
  f.time_of_day_s = 23 * 3600 + 59 * 60 + 59.9;
  f.t_receiver_s = 1700006399.9;  // 2023-11-14 23:59:59.9
  f.has_position = true;
  f.position = {-33.86881234567, 151.20931234567, 58.25};
  f.quality = 2;
  f.satellites = 11;
  f.hdop = 0.7;
  f.speed_mps = 13.5;
  f.course_rad = 1.0;
  f.sigma_lat_m = 0.8;
  f.sigma_lon_m = 0.6;
  f.sigma_alt_m = 1.5;
  const std::string text = encodeRmc(f) + "\n" + encodeGga(f) + "\n" + encodeVtg(f) + "\n" + encodeGst(f) + "\n";
  const NmeaLog l = parseNmeaLog(text);
  ASSERT_EQ(l.fixes.size(), 1u) << text;
  const GnssFix& g = l.fixes[0];
  EXPECT_EQ(l.counters.bad_checksum, 0u);
  const EnuFrame enu(f.position);
  EXPECT_LT(enu.toEnu(g.position).norm(), 1e-3);  // 8 decimals of a minute: ~2e-5 m
  EXPECT_NEAR(g.t_receiver_s, f.t_receiver_s, 0.006);
  EXPECT_NEAR(g.speed_mps, f.speed_mps, 1e-3);
  EXPECT_NEAR(g.course_rad, f.course_rad, 1e-3);
  EXPECT_NEAR(g.sigma_lat_m, 0.8, 1e-9);
  EXPECT_EQ(g.quality, 2);
}

// gnss::parseRmc: the RMC a Velodyne forwards (VLP-16 manual 9.4). The sentence of MRPT's own
// test capture; the expected values from its fields by hand.
TEST(ParseRmc, ParsesGprmcFields) {
  const auto f = parseRmc("$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2E");
  ASSERT_TRUE(f);
  EXPECT_TRUE(f->valid());
  EXPECT_NEAR(f->position.lat_deg, 36.829130930, 1e-9);
  EXPECT_NEAR(f->position.lon_deg, -2.407571547, 1e-9);
  EXPECT_NEAR(f->speed_mps, 0.034 * 0.514444, 1e-5);
  EXPECT_NEAR(f->course_rad, 212.5 * M_PI / 180, 1e-12);
  EXPECT_NEAR(f->time_of_day_s, 8 * 3600 + 18 * 60 + 2, 1e-9);
  EXPECT_NEAR(f->t_receiver_s, 1453364282.0, 1e-6);  // date -u -d '2016-01-21 08:18:02' +%s
}

TEST(ParseRmc, RejectsBadChecksumAndOtherSentencesKeepsAVoidFixsPosition) {
  EXPECT_FALSE(parseRmc("$GPRMC,081802.00,A,3649.7478558,N,00224.4542928,W,0.034,212.5,210116,0.0,E,A*2F"));
  EXPECT_FALSE(parseRmc("$GPGGA,081802.00,3649.7,N,00224.4,W,1,08,0.9,545.4,M,46.9,M,,*47"));
  EXPECT_FALSE(parseRmc(""));
  EXPECT_FALSE(parseRmc("$GPRMC,,,,"));
  EXPECT_FALSE(parseRmc("$GPRMC,081802,A,3699.0,N,00224.4,W,0,0,210116,,"));  // 99 minutes
  EXPECT_FALSE(parseRmc("$GPRMC,081802,V,,,,,,,210116,,"));                    // void, no position
  const auto f = parseRmc("$GPRMC,220632,V,3707.83,S,12139.29,E,0.0,0.0,111212,,");  // no checksum
  ASSERT_TRUE(f);
  EXPECT_FALSE(f->valid());
  EXPECT_EQ(f->rmc_status, 'V');
  EXPECT_NEAR(f->position.lat_deg, -(37 + 7.83 / 60), 1e-12);
  EXPECT_NEAR(f->position.lon_deg, 121 + 39.29 / 60, 1e-12);
}

// The NMEA log parser's defaults are unchanged by the RMC-alone options: a sentence without a
// checksum is counted, a void RMC has no position.
TEST(ParseRmc, LogParserStillRequiresChecksums) {
  const NmeaLog log = parseNmeaLog("$GPRMC,220632,A,3707.83,S,12139.29,E,0.0,0.0,111212,,\n");
  EXPECT_TRUE(log.fixes.empty());
  EXPECT_EQ(log.counters.bad_checksum, 1u);
}
