// NMEA epochs into the rawlog as MRPT CObservationGPS: MRPT's own CRawlog reads them back with the
// receiver's UTC time as the timestamp and the host receive time as originalReceivedTimestamp.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>

#include <filesystem>

#include "roadslam/gnss/nmea.h"
#include "roadslam/rawlog/gps_observation.h"
#include "roadslam/sources/rawlog_source.h"
#include "roadslam/rawlog/rawlog_writer.h"

using namespace roadslam;

TEST(GnssRawlog, NmeaEpochsAreCObservationGps) {
  gnss::GnssFix f;
  f.time_of_day_s = 22 * 3600 + 13 * 60 + 20.5;
  f.t_receiver_s = 1700000000.5;  // 2023-11-14 22:13:20.5 UTC
  f.t_receive_s = 1700000000.58;
  f.has_position = true;
  f.position = {48.137, 11.575, 545.25};
  f.quality = 4;
  f.satellites = 12;
  f.hdop = 0.8;
  f.rmc_status = 'A';
  f.speed_mps = 25.0;
  f.course_rad = M_PI / 2;
  // the same epoch through the NMEA encoder and parser, as roadslam-grab or a log file gives it
  const auto log = gnss::parseNmeaLog("1700000000.58 " + gnss::encodeRmc(f) + "\n1700000000.58 " + gnss::encodeGga(f) +
                                      "\n1700000000.58 " + gnss::encodeVtg(f) + "\n");
  ASSERT_EQ(log.fixes.size(), 1u);
  const auto path = std::filesystem::temp_directory_path() / "roadslam_gnss_test.rawlog";
  {
    rawlog::RawlogWriter w(path.string(), {});
    w.writeGnss(log.fixes[0]);
    w.close();
    EXPECT_EQ(w.gpsWritten(), 1u);
  }
  mrpt::obs::CRawlog rawlog;
  ASSERT_TRUE(rawlog.loadFromRawLogFile(path.string()));
  ASSERT_EQ(rawlog.size(), 1u);
  auto g = std::dynamic_pointer_cast<mrpt::obs::CObservationGPS>(rawlog.getAsObservation(0));
  ASSERT_TRUE(g);
  EXPECT_EQ(g->sensorLabel, "GPS");
  EXPECT_TRUE(g->has_satellite_timestamp);
  EXPECT_NEAR(mrpt::Clock::toDouble(g->timestamp), 1700000000.5, 1e-5);
  EXPECT_NEAR(mrpt::Clock::toDouble(g->originalReceivedTimestamp), 1700000000.58, 1e-5);
  ASSERT_TRUE(g->hasMsgClass<mrpt::obs::gnss::Message_NMEA_GGA>());
  const auto& gga = g->getMsgByClass<mrpt::obs::gnss::Message_NMEA_GGA>().fields;
  EXPECT_NEAR(gga.latitude_degrees, 48.137, 1e-9);
  EXPECT_NEAR(gga.longitude_degrees, 11.575, 1e-9);
  EXPECT_EQ(gga.fix_quality, 4);
  EXPECT_EQ(gga.satellitesUsed, 12u);
  EXPECT_NEAR(gga.HDOP, 0.8, 1e-6);
  EXPECT_NEAR(gga.altitude_meters, 545.25, 1e-3);
  EXPECT_EQ(gga.UTCTime.hour, 22);
  EXPECT_NEAR(gga.UTCTime.sec, 20.5, 1e-6);
  ASSERT_TRUE(g->hasMsgClass<mrpt::obs::gnss::Message_NMEA_RMC>());
  const auto& rmc = g->getMsgByClass<mrpt::obs::gnss::Message_NMEA_RMC>().fields;
  EXPECT_EQ(rmc.validity_char, 'A');
  EXPECT_EQ(rmc.date_day, 14);
  EXPECT_EQ(rmc.date_month, 11);
  EXPECT_EQ(rmc.date_year, 23);
  ASSERT_TRUE(g->hasMsgClass<mrpt::obs::gnss::Message_NMEA_VTG>());
  EXPECT_NEAR(g->getMsgByClass<mrpt::obs::gnss::Message_NMEA_VTG>().fields.ground_speed_kmh, 90.0, 1e-2);
  std::filesystem::remove(path);
}

// A rawlog's CObservationGPS read back as fixes: an RMC + GGA epoch (roadslam-grab's GNSS thread)
// keeps its GGA height, HDOP and quality; a GGA alone (a car's CAN_GPS) is a fix too; a GGA with
// quality 0 is no fix.
TEST(GnssRawlog, RawlogSourceReadsGgaFixes) {
  gnss::GnssFix f;
  f.time_of_day_s = 22 * 3600 + 13 * 60 + 20;
  f.t_receiver_s = 1700000000.0;
  f.t_receive_s = 1700000000.08;
  f.has_position = true;
  f.position = {48.137, 11.575, 545.25};
  f.quality = 1;
  f.hdop = 1.3;
  f.rmc_status = 'A';
  const auto path = std::filesystem::temp_directory_path() / "roadslam_gnss_gga.rawlog";
  {
    mrpt::io::CFileGZOutputStream out(path.string());
    auto ar = mrpt::serialization::archiveFrom(out);
    mrpt::obs::CObservationGPS epoch;
    rawlog::fillGnssObservation(f, "GNSS", epoch);
    ar << epoch;
    mrpt::obs::CObservationGPS gga_only;
    mrpt::obs::gnss::Message_NMEA_GGA gga;
    gga.fields.latitude_degrees = 37.5;
    gga.fields.longitude_degrees = -122.25;
    gga.fields.altitude_meters = 12.5;
    gga.fields.fix_quality = 1;
    gga_only.setMsg(gga);
    gga_only.timestamp = mrpt::Clock::fromDouble(1700000001.0);
    ar << gga_only;
    gga.fields.fix_quality = 0;
    gga_only.setMsg(gga);
    ar << gga_only;
  }
  sources::RawlogPacketSource src(path.string());
  while (!src.finished()) src.next();
  const auto fixes = src.takeDecodedFixes();
  ASSERT_EQ(fixes.size(), 3u);
  EXPECT_TRUE(fixes[0].valid());
  EXPECT_NEAR(fixes[0].position.h_m, 545.25, 1e-3);
  EXPECT_NEAR(fixes[0].hdop, 1.3, 1e-6);
  EXPECT_EQ(fixes[0].quality, 1);
  EXPECT_NEAR(fixes[0].t_receiver_s, 1700000000.0, 1e-3);
  EXPECT_TRUE(fixes[1].valid());
  EXPECT_NEAR(fixes[1].position.lat_deg, 37.5, 1e-9);
  EXPECT_NEAR(fixes[1].position.h_m, 12.5, 1e-9);
  EXPECT_TRUE(std::isnan(fixes[1].hdop));
  EXPECT_FALSE(fixes[2].valid());
  std::filesystem::remove(path);
}
