// Watchdogs (a LiDAR or the CAN bus going silent and coming back) and session files
// (calibration copied and stored in the scans).
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/serialization/CArchive.h>

#include <fstream>

#include "grab_test_util.h"
#include "roadslam/grabber/grabber.h"

using namespace roadslam;
using namespace roadslam::grabber;
using test::sendCan;

TEST(GrabWatchdog, ReportsASilentSensorAndItsReturn) {
  const auto& pkts = test::simPackets(0.3);
  test::TempDir dir("wd");
  Grabber g(test::paramsFromText(test::testIni()), dir.str());
  g.start();
  test::sendPaced(pkts, g.dataPort(0), g.positionPort(0), 1.0);
  EXPECT_TRUE(g.status().events.empty());
  std::this_thread::sleep_for(std::chrono::milliseconds(700));  // silent_after_ms = 400
  GrabStatus st = g.status();
  ASSERT_EQ(st.events.size(), 1u);
  EXPECT_NE(st.events[0].find("silent"), std::string::npos) << st.events[0];
  EXPECT_TRUE(st.sensors[0].silent);
  test::sendPaced(pkts, g.dataPort(0), g.positionPort(0), 1.0);
  st = g.status();
  ASSERT_EQ(st.events.size(), 1u);
  EXPECT_NE(st.events[0].find("receiving again"), std::string::npos) << st.events[0];
  EXPECT_EQ(st.sensors[0].silent_events, 1u);
  EXPECT_NE(Grabber::formatStatus(st).find("LIDAR"), std::string::npos);
  g.stop();
}

TEST(GrabWatchdog, ReportsASilentCanBusAndItsReturn) {
  test::TempDir dir("wdcan");
  Grabber g(test::paramsFromText(test::testIni("can = can\n[can]\nsource = none\nsilent_after_ms = 300\n")),
            dir.str());
  int sv[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv), 0);
  g.useCanSocket(sv[0], "can0");
  g.start();
  auto canEvents = [&] {
    std::vector<std::string> out;
    for (const auto& e : g.status().events)
      if (e.rfind("CAN", 0) == 0) out.push_back(e);
    return out;
  };
  std::size_t bus_off = 0;
  sendCan(sv[1], 20, &bus_off);
  EXPECT_TRUE(canEvents().empty());
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  auto ev = canEvents();
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_NE(ev[0].find("silent"), std::string::npos) << ev[0];
  EXPECT_TRUE(g.status().can.silent);
  sendCan(sv[1], 5, &bus_off);
  std::this_thread::sleep_for(std::chrono::milliseconds(150));  // < silent_after_ms
  ev = canEvents();
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0], "CAN: receiving again");
  g.stop();
  ::close(sv[1]);
  EXPECT_EQ(g.status().can.silent_events, 1u);
  EXPECT_EQ(g.status().can.frames, 25u);
}

// A sensor's VeloView calibration: copied into the session folder and stored in every scan.
TEST(GrabSession, CalibrationCopiedAndStoredInTheScans) {
  const std::string xml = std::string(ROADSLAM_SHARED_DATA) + "/velodyne/veloview_calib_VLP-16.xml";
  if (!std::filesystem::exists(xml)) GTEST_SKIP() << "missing " << xml;
  const auto& pkts = test::simPackets(0.3);
  test::TempDir dir("calib");
  // The shipped XML equals MRPT's default; give laser 0 a distance correction to tell them apart.
  std::string text = test::readAll(xml);
  const auto at = text.find("<distCorrection_>0");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 18, "<distCorrection_>7");
  const std::string mine = dir.str() + "/mine.xml";
  std::ofstream(mine) << text;
  Grabber g(test::paramsFromText(test::testIni("", "calibration_file = " + mine + "\n")), dir.str() + "/s");
  g.start();
  test::sendPaced(pkts, g.dataPort(0), g.positionPort(0), 1.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  g.stop();
  EXPECT_EQ(test::readAll(dir.str() + "/s/lidar.calibration.xml"), text);
  mrpt::obs::VelodyneCalibration ref;
  ASSERT_TRUE(ref.loadFromXMLFile(mine));
  const auto def = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration("VLP16");
  ASSERT_NE(ref.laser_corrections[0].distanceCorrection, def.laser_corrections[0].distanceCorrection);
  mrpt::io::CFileGZInputStream in(dir.str() + "/s/grab_000.rawlog");
  auto ar = mrpt::serialization::archiveFrom(in);
  mrpt::obs::CObservationVelodyneScan::Ptr scan;
  for (int i = 0; i < 10 && !scan; ++i)  // the first records may be GPS
    scan = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(ar.ReadObject());
  ASSERT_TRUE(scan);
  ASSERT_EQ(scan->calibration.laser_corrections.size(), ref.laser_corrections.size());
  for (std::size_t i = 0; i < ref.laser_corrections.size(); ++i)
    EXPECT_DOUBLE_EQ(scan->calibration.laser_corrections[i].distanceCorrection,
                     ref.laser_corrections[i].distanceCorrection);
}
