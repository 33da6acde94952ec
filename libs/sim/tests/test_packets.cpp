// Oracle tests of the simulator's packets: the velodyne decoder gives back the true returns,
// timestamps agree with capture times and ground truth, and runs are byte-deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "roadslam/pcap/pcap_reader.h"
#include "roadslam/sim/outputs.h"
#include "roadslam/velodyne/decoder.h"
#include "roadslam/velodyne/position.h"
#include "sim_test_util.h"

using namespace roadslam;
using namespace roadslam::sim;
using sim::test::iniPath;

TEST(SimPackets, DecoderReproducesTheTrueReturns) {
  ScenarioParams p = ScenarioParams::fromFile(iniPath("urban-loop.ini"));
  p.duration_s = 1.0;
  p.trajectory.start_standing_s = 0.2;  // moving for most of the second
  Simulator sim(p);
  test::VectorSink sink;
  std::vector<TrueReturn> truth;
  const SimStats st = sim.run(sink, &truth);
  ASSERT_EQ(st.lidar.returns, truth.size());
  ASSERT_GT(truth.size(), 200000u);
  const velodyne::Decoder dec;
  std::vector<ScanPoint> pts;
  std::size_t next = 0, data_packets = 0;
  double max_dr = 0, max_daz = 0, max_dt = 0;
  for (const auto& pk : sink.packets) {
    if (pk.port != velodyne::kDefaultDataPort) continue;
    pts.clear();
    velodyne::PacketInfo info;
    ASSERT_EQ(dec.decode(pk.bytes.data(), pk.bytes.size(), pts, &info), velodyne::DecodeStatus::Ok);
    ASSERT_EQ(info.timestamp_us, sim.packetTimestampUs(data_packets));
    const double t0 = static_cast<double>(data_packets) * LidarSimulator::packetPeriod_s();
    for (const ScanPoint& q : pts) {
      ASSERT_LT(next, truth.size());
      const TrueReturn& r = truth[next++];
      ASSERT_EQ(r.packet, data_packets);
      const double range = std::sqrt(double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
      double az = std::atan2(-double(q.y), double(q.x)) * 180.0 / M_PI;
      if (az < 0) az += 360;
      max_dr = std::max(max_dr, std::abs(range - r.range_m));
      max_daz = std::max(max_daz, std::abs(std::remainder(az - r.azimuth_deg, 360.0)));
      max_dt = std::max(max_dt, std::abs(q.t - (r.t_s - t0)));
      ASSERT_EQ(q.ring, r.ring);
      ASSERT_EQ(static_cast<uint8_t>(q.intensity), r.intensity);
    }
    ++data_packets;
  }
  EXPECT_EQ(next, truth.size()) << "every true return decoded once, in firing order";
  EXPECT_EQ(data_packets, st.data_packets);
  EXPECT_LE(max_dr, 0.002 + 1e-4) << "2 mm distance unit";
  EXPECT_LE(max_daz, 0.01) << "0.01 deg azimuth unit (measured 0.0065 deg)";
  EXPECT_LE(max_dt, 1e-6);
  RecordProperty("max_range_error_m", std::to_string(max_dr));
  RecordProperty("max_azimuth_error_deg", std::to_string(max_daz));
}

TEST(SimPackets, TimestampsCaptureTimesAndGroundTruthAgree) {
  test::TempDir dir("stamps");
  ScenarioParams p = ScenarioParams::fromFile(iniPath("urban-loop.ini"));
  p.duration_s = 2.5;
  p.start_epoch_s = 1700006399;  // 1 s before the top of the hour: the timestamp wraps inside the run
  Simulator sim(p);
  OutputOptions opt;
  opt.dir = dir.str();
  const RunReport rep = runToDirectory(sim, opt);
  const double P = LidarSimulator::packetPeriod_s();

  pcap::PcapReader reader(dir.str() + "/velodyne.pcap");
  pcap::UdpDatagram d;
  std::size_t data = 0, position = 0;
  double first_data = -1;
  std::vector<std::pair<double, gnss::GnssFix>> fixes;
  while (reader.next(d) == pcap::ReadStatus::Ok) {
    if (d.dst_port == velodyne::kDefaultDataPort) {
      ASSERT_EQ(d.payload.size(), velodyne::kDataPacketSize);
      const uint32_t ts = d.payload[1200] | (d.payload[1201] << 8) | (d.payload[1202] << 16) |
                          (static_cast<uint32_t>(d.payload[1203]) << 24);
      const double first_firing = d.stamp_s - P;  // captured when the packet's span is complete
      const double hour = std::floor(first_firing / 3600.0 + 1e-9) * 3600.0;
      ASSERT_NEAR(hour + ts * 1e-6, first_firing, 2e-6) << "packet " << data;
      if (first_data < 0) first_data = d.stamp_s;
      ++data;
    } else {
      ASSERT_EQ(d.dst_port, velodyne::kDefaultPositionPort);
      velodyne::PositionPacket pp;
      ASSERT_TRUE(velodyne::decodePositionPacket(d.payload.data(), d.payload.size(), pp));
      ASSERT_TRUE(pp.fix) << pp.nmea;
      EXPECT_NEAR(pp.fix->t_receiver_s, d.stamp_s, 0.006) << pp.nmea;
      fixes.emplace_back(d.stamp_s, *pp.fix);
      ++position;
    }
  }
  ASSERT_EQ(reader.status(), pcap::ReadStatus::EndOfFile);
  EXPECT_EQ(data, rep.stats.data_packets);
  EXPECT_EQ(position, 3u);  // t = 0, 1, 2 s
  EXPECT_NEAR(first_data, static_cast<double>(p.start_epoch_s) + P, 2e-6);

  std::ifstream tum(dir.str() + "/gt_trajectory.tum");
  std::vector<std::array<double, 8>> gt;
  std::array<double, 8> row{};
  while (tum >> row[0] >> row[1] >> row[2] >> row[3] >> row[4] >> row[5] >> row[6] >> row[7]) gt.push_back(row);
  ASSERT_EQ(gt.size(), static_cast<std::size_t>(std::floor(rep.stats.duration_s / 0.01)) + 1);
  EXPECT_DOUBLE_EQ(gt.front()[0], static_cast<double>(p.start_epoch_s));
  for (std::size_t i = 1; i < gt.size(); ++i) ASSERT_NEAR(gt[i][0] - gt[i - 1][0], 0.01, 2e-6);
  // gt_vehicle.csv (vehicle reference) and the TUM (lidar) are one rigid mount apart.
  std::ifstream csv(dir.str() + "/gt_vehicle.csv");
  std::string line;
  std::getline(csv, line);
  ASSERT_EQ(line.rfind("t,x,y,z,yaw_rad", 0), 0u) << line;
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    double v[13];
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2],
                          &v[3], &v[4], &v[5], &v[6], &v[7], &v[8], &v[9], &v[10], &v[11], &v[12]), 13);
    ASSERT_LT(rows, gt.size());
    const auto& g = gt[rows++];
    ASSERT_DOUBLE_EQ(v[0], g[0]);
    // flat start: lidar = vehicle + R(yaw) (mount_x, mount_y, mount_height)
    EXPECT_NEAR(g[1], v[1] + std::cos(v[4]) * p.lidar.mount_x_m - std::sin(v[4]) * p.lidar.mount_y_m, 1e-3);
    EXPECT_NEAR(g[2], v[2] + std::sin(v[4]) * p.lidar.mount_x_m + std::cos(v[4]) * p.lidar.mount_y_m, 1e-3);
    EXPECT_NEAR(g[3], v[3] + p.lidar.mount_height_m, 1e-3);
  }
  EXPECT_EQ(rows, gt.size());
  // $GPRMC gives the vehicle reference; the lidar is mount_x_m ahead of it (standing, yaw 0).
  for (const auto& [stamp, fix] : fixes) {
    const std::size_t i = static_cast<std::size_t>(std::llround((stamp - gt.front()[0]) / 0.01));
    ASSERT_LT(i, gt.size());
    const double y = (fix.position.lat_deg - p.origin_lat_deg) * M_PI / 180.0 * 6378137.0;
    const double x = (fix.position.lon_deg - p.origin_lon_deg) * M_PI / 180.0 * 6378137.0 *
                     std::cos(p.origin_lat_deg * M_PI / 180.0);
    EXPECT_NEAR(gt[i][1] - x, p.lidar.mount_x_m, 0.2) << "t " << stamp;  // NMEA: 1e-4 minute = 0.19 m
    EXPECT_NEAR(gt[i][2] - y, 0.0, 0.2);
  }
}

TEST(SimPackets, SameSeedSameBytesOtherSeedOtherBytes) {
  auto pcapOf = [](uint64_t seed, const std::string& tag) {
    test::TempDir dir(tag);
    ScenarioParams p = ScenarioParams::fromFile(iniPath("parallel-streets.ini"));
    p.duration_s = 0.5;
    p.seed = seed;
    Simulator sim(p);
    OutputOptions opt;
    opt.dir = dir.str();
    runToDirectory(sim, opt);
    return test::readAll(dir.str() + "/velodyne.pcap");
  };
  const std::string a = pcapOf(7, "a"), b = pcapOf(7, "b"), c = pcapOf(8, "c");
  ASSERT_GT(a.size(), 300000u);
  EXPECT_TRUE(a == b) << "same seed, same bytes";
  EXPECT_EQ(a.size(), c.size());
  EXPECT_FALSE(a == c) << "another seed, another world and noise";
}

// Frames: decoded points (decoder's lidar frame) mapped by the ground-truth pose T_world_lidar at
// each point's firing time land on the true surface points, within range noise and mount jitter.
TEST(SimPackets, DecodedPointsMappedByGroundTruthLandOnTheWorld) {
  ScenarioParams p = ScenarioParams::fromFile(iniPath("hills.ini"));
  p.duration_s = 0.3;
  p.trajectory.start_standing_s = 0;  // moving, pitching and rolling on the hills
  p.lidar.range_noise_m = 0.0;
  p.lidar.jitter_deg = 0.0;
  Simulator sim(p);
  test::VectorSink sink;
  std::vector<TrueReturn> truth;
  sim.run(sink, &truth);
  const velodyne::Decoder dec;
  std::vector<ScanPoint> pts;
  std::size_t next = 0, k = 0;
  double max_err = 0, sum_err = 0;
  for (const auto& pk : sink.packets) {
    if (pk.port != velodyne::kDefaultDataPort) continue;
    pts.clear();
    ASSERT_EQ(dec.decode(pk.bytes.data(), pk.bytes.size(), pts), velodyne::DecodeStatus::Ok);
    const double t0 = static_cast<double>(k++) * LidarSimulator::packetPeriod_s();
    for (const ScanPoint& q : pts) {
      const TrueReturn& r = truth[next++];
      // the simulator holds one pose per 55 us firing sequence
      const double t_seq = t0 + (r.sequence) * velodyne::kVlp16SequencePeriod_s;
      const Vec3 w = sim.lidar().lidarPose(t_seq).apply({q.x, q.y, q.z});
      const double e = std::sqrt((w.x - r.p_world.x) * (w.x - r.p_world.x) + (w.y - r.p_world.y) * (w.y - r.p_world.y) +
                                 (w.z - r.p_world.z) * (w.z - r.p_world.z));
      max_err = std::max(max_err, e);
      sum_err += e;
    }
  }
  ASSERT_EQ(next, truth.size());
  // 1 mm distance rounding + 0.01 deg azimuth at <= 100 m (17 mm) + float coordinates
  EXPECT_LT(max_err, 0.02);
  EXPECT_LT(sum_err / static_cast<double>(next), 0.005);
}
