// CAN from a real candump log (the RAV4 minute) through the grabber: every frame in the candump
// sidecar, and as many vehicle observations as libs/vehicle's own batch export makes (oracle).
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CRawlog.h>

#include <cmath>

#include "grab_test_util.h"
#include "roadslam/can/candump.h"
#include "roadslam/can/dbc.h"
#include "roadslam/can/encoder.h"
#include "roadslam/grabber/grabber.h"
#include "roadslam/vehicle/dead_reckoning.h"
#include "roadslam/vehicle/rawlog_export.h"

using namespace roadslam;
using namespace roadslam::grabber;

TEST(GrabCan, RealCandumpReplayDecodedLikeTheVehicleExport) {
  const std::string log = std::string(ROADSLAM_SHARED_DATA) + "/can/rav4-2017/rav4_2018-08-02_seg40.candump.log";
  if (!std::filesystem::exists(log)) GTEST_SKIP() << "missing " << log;
  const std::string vini = std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/toyota-rav4-2017.ini";
  const auto frames = can::readCandumpFile(log);
  test::TempDir dir("can");
  // As fast as possible, log stamps kept (restamp = false), a queue that holds the whole minute.
  const std::string ini = test::testIni("can = can\ncan_queue_capacity = 200000\n[can]\nsource = candump\n"
                                        "candump_realtime = false\nrestamp = false\ncandump_file = " +
                                        log + "\nvehicle_ini = " + vini + "\n");
  Grabber g(test::paramsFromText(ini), dir.str());
  g.start();
  for (int i = 0; i < 600 && g.status().can.frames < frames.size(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  g.stop();
  const GrabStatus st = g.status();
  EXPECT_EQ(st.can.frames, frames.size());
  EXPECT_EQ(st.can.queue_drops, 0u);
  EXPECT_EQ(can::readCandumpFile(dir.str() + "/can_000.candump.log"), frames);  // lossless sidecar

  vehicle::VehicleDecoder dec(vehicle::loadVehicleIni(vini));
  const auto ref = vehicle::exportRawlog(frames, dec, vehicle::DeadReckoningParams{}, vehicle::RawlogExportParams{},
                                         dir.str() + "/oracle.rawlog");
  ASSERT_GT(ref.odometry, 1000u);
  EXPECT_EQ(st.can.vehicle_observations, ref.odometry + ref.imu);
  EXPECT_EQ(st.writer.observations, st.can.vehicle_observations + st.writer.sweeps + st.writer.gps);
}

// GNSS from the CAN bus (Tesla MCU_locationStatus / MCU_locationStatus2, opendbc tesla_can): frames
// encoded with the DBC from known positions come out of the grabber as CAN_GPS observations at those
// positions (to the DBC's 1e-6 deg and 0.1 m resolution), as many as libs/vehicle's batch export makes.
TEST(GrabCan, TeslaGnssFramesBecomeGpsObservations) {
  const std::string vini = std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/tesla-model-s.ini";
  const vehicle::VehicleParams vp = vehicle::loadVehicleIni(vini);
  if (!std::filesystem::exists(vp.dbcPath())) GTEST_SKIP() << "missing " << vp.dbcPath();
  const can::Database db = can::loadDbcFile(vp.dbcPath());
  const can::MessageEncoder loc(*db.findMessage("MCU_locationStatus")), elev(*db.findMessage("MCU_locationStatus2"));
  std::vector<can::CanFrame> frames;
  auto position = [](int k) { return std::pair<double, double>{37.4191 + 2.5e-5 * k, -122.0754 - 1.5e-5 * k}; };
  for (int k = 0; k < 20; ++k) {
    const std::int64_t t_us = 1700000000000000LL + k * 100000;
    std::vector<double> e(elev.size(), 0.0);
    e[elev.index("MCU_elevation")] = 31.4 + 0.1 * k;
    can::CanFrame f;
    elev.encode(e.data(), t_us, f);
    f.setInterface("can0");
    frames.push_back(f);
    std::vector<double> v(loc.size(), 0.0);
    v[loc.index("MCU_latitude")] = position(k).first;
    v[loc.index("MCU_longitude")] = position(k).second;
    v[loc.index("MCU_gpsAccuracy")] = 2.0;
    loc.encode(v.data(), t_us + 1000, f);
    f.setInterface("can0");
    frames.push_back(f);
  }
  test::TempDir dir("can_gnss");
  const std::string log = dir.str() + "/tesla.candump.log";
  can::writeCandumpFile(log, frames);
  const std::string ini = test::testIni("can = can\n[can]\nsource = candump\ncandump_realtime = false\nrestamp = false\n"
                                        "candump_file = " + log + "\nvehicle_ini = " + vini + "\n");
  Grabber g(test::paramsFromText(ini), dir.str() + "/out");
  g.start();
  for (int i = 0; i < 100 && g.status().can.frames < frames.size(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  g.stop();
  const GrabStatus st = g.status();
  EXPECT_EQ(st.can.frames, frames.size());
  EXPECT_EQ(st.writer.write_errors, 0u) << st.writer.error;
  mrpt::obs::CRawlog rawlog;
  ASSERT_TRUE(rawlog.loadFromRawLogFile(dir.str() + "/out/grab_000.rawlog"));
  std::size_t n = 0;
  for (std::size_t i = 0; i < rawlog.size(); ++i) {
    auto gps = std::dynamic_pointer_cast<mrpt::obs::CObservationGPS>(rawlog.getAsObservation(i));
    if (!gps) continue;
    EXPECT_EQ(gps->sensorLabel, "CAN_GPS");
    const int k = int(std::lround((mrpt::Clock::toDouble(gps->timestamp) - 1700000000.001) / 0.1));
    const auto& gga = gps->getMsgByClass<mrpt::obs::gnss::Message_NMEA_GGA>().fields;
    EXPECT_NEAR(gga.latitude_degrees, position(k).first, 0.6e-6);
    EXPECT_NEAR(gga.longitude_degrees, position(k).second, 0.6e-6);
    EXPECT_NEAR(gga.altitude_meters, 31.4 + 0.1 * k, 0.051);
    ++n;
  }
  EXPECT_EQ(n, 20u);
  vehicle::VehicleDecoder dec(vp);
  const auto ref = vehicle::exportRawlog(frames, dec, vehicle::DeadReckoningParams{}, vehicle::RawlogExportParams{},
                                         dir.str() + "/oracle.rawlog");
  EXPECT_EQ(ref.gps, n);
}
