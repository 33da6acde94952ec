// Rawlog export: the observations read back with MRPT carry the decoded values, the odometry equals
// the dead reckoning, and the candump sidecar holds the input frames unchanged.
#include <roadslam/can/candump.h>
#include <roadslam/vehicle/can_odometry.h>
#include <roadslam/vehicle/rawlog_export.h>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/serialization/CArchive.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace roadslam::vehicle;
using roadslam::can::CanFrame;

namespace {
const char* kExportDbc = R"(BO_ 100 WHEELS: 8 X
 SG_ FL : 0|16@1+ (0.01,0) [0|0] "km/h" X
 SG_ FR : 16|16@1+ (0.01,0) [0|0] "km/h" X
 SG_ RL : 32|16@1+ (0.01,0) [0|0] "km/h" X
 SG_ RR : 48|16@1+ (0.01,0) [0|0] "km/h" X
BO_ 101 YAW: 2 X
 SG_ RATE : 0|16@1- (0.01,0) [0|0] "deg/s" X
BO_ 102 GPS: 8 X
 SG_ LAT : 0|32@1- (1e-7,0) [0|0] "deg" X
 SG_ LON : 32|32@1- (1e-7,0) [0|0] "deg" X
)";

VehicleParams params() {
  VehicleParams p;
  p.name = "test";
  const char* w[4] = {"WHEELS.FL", "WHEELS.FR", "WHEELS.RL", "WHEELS.RR"};
  for (int i = 0; i < 4; ++i) p.map[static_cast<std::size_t>(i)] = {w[i], "", "", "kmh", unitScale("kmh"), 1.0};
  p.map[static_cast<std::size_t>(Quantity::kYawRate)] = {"YAW.RATE", "", "", "deg_s", unitScale("deg_s"), 1.0};
  p.map[static_cast<std::size_t>(Quantity::kLatitude)] = {"GPS.LAT", "", "", "deg_wgs84", 1.0, 1.0};
  p.map[static_cast<std::size_t>(Quantity::kLongitude)] = {"GPS.LON", "", "", "deg_wgs84", 1.0, 1.0};
  return p;
}

std::vector<CanFrame> frames() {
  std::vector<CanFrame> out;
  for (int i = 0; i < 200; ++i) {
    CanFrame w;
    w.t_us = 1700000000000000LL + i * 20000;
    w.setInterface("can0");
    w.id = 100;
    w.len = 8;
    for (int k = 0; k < 4; ++k) w.data[2 * k] = 0xE8, w.data[2 * k + 1] = 0x03;  // 10.00 km/h
    out.push_back(w);
    CanFrame y = w;
    y.t_us += 5000;
    y.id = 101;
    y.len = 2;
    y.data = {0xF4, 0x01};  // 5.00 deg/s
    out.push_back(y);
    if (i % 50 == 0) {
      CanFrame g = w;
      g.t_us += 7000;
      g.id = 102;
      const std::int32_t lat = 377210000, lon = -1224722991;
      std::memcpy(g.data.data(), &lat, 4);
      std::memcpy(g.data.data() + 4, &lon, 4);
      out.push_back(g);
    }
  }
  return out;
}
}  // namespace

TEST(RawlogExport, ObservationsReadBackAndSidecarIsLossless) {
  const std::string path = ::testing::TempDir() + "/roadslam_can_export.rawlog";
  const auto input = frames();
  VehicleDecoder dec(params(), roadslam::can::parseDbc(kExportDbc));
  const RawlogExportStats st = exportRawlog(input, dec, DeadReckoningParams{}, RawlogExportParams{}, path);
  VehicleDecoder dec2(params(), roadslam::can::parseDbc(kExportDbc));
  const OdometryResult ref = runOdometry(input, dec2, DeadReckoningParams{});
  EXPECT_EQ(st.odometry, ref.poses.size() - 1);  // runOdometry also lists the start pose
  EXPECT_EQ(st.imu, 200U);
  EXPECT_EQ(st.gps, 4U);

  mrpt::io::CFileGZInputStream in(path);
  auto ar = mrpt::serialization::archiveFrom(in);
  std::size_t n_odo = 0, n_imu = 0, n_gps = 0;
  mrpt::obs::CObservationOdometry::Ptr last_odo;
  for (;;) {
    mrpt::serialization::CSerializable::Ptr obj;
    try {
      obj = ar.ReadObject();
    } catch (const std::exception&) {
      break;  // end of file
    }
    if (auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obj)) {
      ++n_odo;
      last_odo = o;
      EXPECT_TRUE(o->hasVelocities);
      EXPECT_NEAR(o->velocityLocal.vx, 10.0 / 3.6, 1e-9);
      EXPECT_EQ(o->sensorLabel, "CAN_ODOMETRY");
    } else if (auto m = std::dynamic_pointer_cast<mrpt::obs::CObservationIMU>(obj)) {
      ++n_imu;
      EXPECT_NEAR(m->get(mrpt::obs::IMU_WZ), 5.0 * M_PI / 180, 1e-12);
    } else if (auto g = std::dynamic_pointer_cast<mrpt::obs::CObservationGPS>(obj)) {
      ++n_gps;
      ASSERT_TRUE(g->hasMsgClass<mrpt::obs::gnss::Message_NMEA_GGA>());
      EXPECT_NEAR(g->getMsgByClass<mrpt::obs::gnss::Message_NMEA_GGA>().fields.latitude_degrees, 37.721, 1e-7);
    }
  }
  EXPECT_EQ(n_odo, st.odometry);
  EXPECT_EQ(n_imu, st.imu);
  EXPECT_EQ(n_gps, st.gps);
  ASSERT_TRUE(last_odo);
  EXPECT_NEAR(last_odo->odometry.x(), ref.poses.back().x_m, 1e-9);
  EXPECT_NEAR(last_odo->odometry.phi(), ref.poses.back().yaw_rad, 1e-9);
  EXPECT_EQ(roadslam::can::readCandumpFile(st.sidecar_path), input);
}
