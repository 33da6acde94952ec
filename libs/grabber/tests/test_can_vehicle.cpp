// CAN from a real candump log (the RAV4 minute) through the grabber: every frame in the candump
// sidecar, and as many vehicle observations as libs/vehicle's own batch export makes (oracle).
#include <gtest/gtest.h>

#include "grab_test_util.h"
#include "roadslam/can/candump.h"
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
