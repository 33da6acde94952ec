// Rawlog round trip: packets -> RawlogWriter -> RawlogPacketSource gives byte-identical payloads,
// and MRPT's own CRawlog loader opens the file (so RawLogViewer / rawlog-edit can).
#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <filesystem>
#include <cstring>
#include <fstream>
#include <iterator>

#include "roadslam/sources/rawlog_source.h"
#include "roadslam/rawlog/rawlog_writer.h"
#include "test_packets.h"

using namespace roadslam::sources;
using namespace roadslam::rawlog;
using namespace roadslam::sources::test_support;
namespace fs = std::filesystem;

namespace {

struct Recording {
  std::vector<std::vector<roadslam::velodyne::RawPacket>> sweeps;
  std::vector<roadslam::velodyne::RawPacket> positions;
};

Recording makeRecording(int n_sweeps, int packets_per_sweep) {
  Recording r;
  const double t0 = 1453364282.0;  // 2016-01-21 08:18:02 UTC
  int k = 0;
  for (int s = 0; s < n_sweeps; ++s) {
    r.sweeps.emplace_back();
    for (int i = 0; i < packets_per_sweep; ++i, ++k) {
      const uint32_t t_us = uint32_t(k * 1327104LL / 1000);
      roadslam::velodyne::RawPacket p;
      p.stamp_s = t0 + t_us * 1e-6;
      p.dst_port = 2368;
      p.payload = makeDataPacket(t_us, uint16_t(i * 36000 / packets_per_sweep), 7 + k);
      r.sweeps.back().push_back(p);
    }
    roadslam::velodyne::RawPacket g;
    g.stamp_s = r.sweeps.back().back().stamp_s;
    g.dst_port = 8308;
    g.payload = makePositionPacket(uint32_t(k * 1327), kAlmeriaRmc);
    r.positions.push_back(g);
  }
  return r;
}

fs::path tempDir() {
  const fs::path d = fs::temp_directory_path() / ("roadslam_sources_" + std::to_string(getpid()));
  fs::create_directories(d);
  return d;
}

void write(const fs::path& path, const Recording& r) {
  RawlogWriter w(path.string(), RawlogWriter::Params{});
  for (std::size_t s = 0; s < r.sweeps.size(); ++s) {
    w.writeSweep(r.sweeps[s]);
    EXPECT_TRUE(w.writePosition(r.positions[s]));
  }
  w.close();
}

}  // namespace

TEST(Rawlog, PacketsRoundTripByteIdenticalWithStamps) {
  const Recording rec = makeRecording(3, 76);
  const fs::path path = tempDir() / "roundtrip.rawlog";
  write(path, rec);

  RawlogPacketSource src(path.string());
  std::size_t k = 0;
  for (const auto& sweep : rec.sweeps)
    for (const auto& expected : sweep) {
      auto p = src.next();
      ASSERT_TRUE(p) << "packet " << k;
      EXPECT_EQ(p->payload, expected.payload) << "packet " << k;
      EXPECT_NEAR(p->stamp_s, expected.stamp_s, 2e-6) << "packet " << k;
      EXPECT_EQ(p->dst_port, 2368);
      ++k;
    }
  EXPECT_FALSE(src.next());
  EXPECT_TRUE(src.finished());
  EXPECT_EQ(src.scansRead(), 3u);
  EXPECT_EQ(src.stats().data_packets, 3u * 76u);
  EXPECT_EQ(src.stats().missing_packets, 0u);
  const auto fixes = src.takeDecodedFixes();
  ASSERT_EQ(fixes.size(), 3u);
  EXPECT_TRUE(src.takeDecodedFixes().empty()) << "fixes are handed out once";
  EXPECT_NEAR(fixes[0].position.lat_deg, kAlmeriaLat_deg, 1e-7);
  EXPECT_NEAR(fixes[0].position.lon_deg, kAlmeriaLon_deg, 1e-7);
  EXPECT_TRUE(fixes[0].valid());
  EXPECT_NEAR(fixes[0].time_of_day_s, 8 * 3600 + 18 * 60 + 2, 1e-6);
  EXPECT_NEAR(fixes[0].t_receiver_s, 1453334400.0 + 8 * 3600 + 18 * 60 + 2, 1e-6);  // 2016-01-21
  EXPECT_NEAR(fixes[0].t_receive_s, rec.positions[0].stamp_s, 1e-6);
  fs::remove(path);
}

TEST(Rawlog, MrptCRawlogOpensOurFile) {
  const Recording rec = makeRecording(2, 10);
  const fs::path path = tempDir() / "mrpt.rawlog";
  write(path, rec);

  mrpt::obs::CRawlog rawlog;
  ASSERT_TRUE(rawlog.loadFromRawLogFile(path.string()));
  ASSERT_EQ(rawlog.size(), 4u);
  auto scan = rawlog.getAsObservation(0);
  auto v = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(scan);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->sensorLabel, "VELODYNE");
  ASSERT_EQ(v->scan_packets.size(), 10u);
  EXPECT_EQ(v->scan_packets[3].gps_timestamp(), uint32_t(3 * 1327104LL / 1000));
  EXPECT_FALSE(v->calibration.empty());
  auto g = std::dynamic_pointer_cast<mrpt::obs::CObservationGPS>(rawlog.getAsObservation(1));
  ASSERT_TRUE(g);
  EXPECT_TRUE(g->hasMsgClass<mrpt::obs::gnss::Message_NMEA_RMC>());
  fs::remove(path);
}

TEST(Rawlog, UnclosedWriterLeavesNoFileAndBadPathsAreNamed) {
  const fs::path path = tempDir() / "aborted.rawlog";
  {
    RawlogWriter w(path.string(), RawlogWriter::Params{});
    w.writeSweep(makeRecording(1, 5).sweeps[0]);
  }
  EXPECT_FALSE(fs::exists(path));
  try {
    RawlogWriter w("/nonexistent-dir/x.rawlog", RawlogWriter::Params{});
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.rawlog"), std::string::npos) << e.what();
  }
  try {
    RawlogPacketSource src("/nonexistent-dir/y.rawlog");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/y.rawlog"), std::string::npos) << e.what();
  }
}

TEST(Rawlog, PositionPacketWithoutNmeaIsCountedNotWritten) {
  const fs::path path = tempDir() / "nonmea.rawlog";
  RawlogWriter w(path.string(), RawlogWriter::Params{});
  roadslam::velodyne::RawPacket empty;
  empty.dst_port = 8308;
  empty.payload.assign(512, 0);  // early VLP-16 firmware: empty NMEA field (VeloView capture)
  EXPECT_FALSE(w.writePosition(empty));
  EXPECT_EQ(w.skippedPackets(), 1u);
  EXPECT_EQ(w.gpsWritten(), 0u);
  w.close();
  fs::remove(path);
}

TEST(Rawlog, ReadsTheSensoryFrameFormatToo) {
  // The older "actions + sensory frames" layout, as written by MRPT's CRawlog.
  const Recording rec = makeRecording(2, 8);
  const fs::path path = tempDir() / "sf.rawlog";
  {
    mrpt::obs::CRawlog rawlog;
    for (const auto& sweep : rec.sweeps) {
      auto v = mrpt::obs::CObservationVelodyneScan::Create();
      for (const auto& p : sweep) {
        v->scan_packets.emplace_back();
        std::memcpy(&v->scan_packets.back(), p.payload.data(), p.payload.size());
      }
      v->timestamp = mrpt::Clock::fromDouble(sweep.front().stamp_s);
      mrpt::obs::CSensoryFrame sf;
      sf.insert(v);
      rawlog.insert(sf);
    }
    ASSERT_TRUE(rawlog.saveToRawLogFile(path.string()));
  }
  RawlogPacketSource src(path.string());
  std::size_t k = 0;
  while (auto p = src.next()) {
    EXPECT_EQ(p->payload, rec.sweeps[k / 8][k % 8].payload) << "packet " << k;
    ++k;
  }
  EXPECT_EQ(k, 16u);
  EXPECT_EQ(src.scansRead(), 2u);
  EXPECT_TRUE(src.errorMessage().empty()) << src.errorMessage();
  fs::remove(path);
}

TEST(Rawlog, TruncatedOrForeignFilesReportAnErrorNamingTheFile) {
  const fs::path good = tempDir() / "good.rawlog";
  write(good, makeRecording(4, 76));
  const fs::path cut = tempDir() / "cut.rawlog";
  {
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size() / 2));
  }
  RawlogPacketSource src(cut.string());
  std::size_t n = 0;
  while (src.next()) ++n;
  EXPECT_LT(n, 4u * 76u);
  EXPECT_NE(src.errorMessage().find(cut.string()), std::string::npos) << src.errorMessage();

  const fs::path text = tempDir() / "notes.rawlog";
  std::ofstream(text) << "this is not an MRPT archive\n";
  RawlogPacketSource foreign(text.string());
  EXPECT_FALSE(foreign.next());
  EXPECT_NE(foreign.errorMessage().find(text.string()), std::string::npos);
  for (const auto& p : {good, cut, text}) fs::remove(p);
}

TEST(Rawlog, WriterParamsRoundTripThroughIniWithDegreeKeys) {
  RawlogWriter::Params p;
  p.sensor_label = "VLP16_ROOF";
  p.model = "HDL32";
  p.min_range_m = 0.5;
  p.z_m = 1.73;
  p.yaw_rad = M_PI / 2;
  mrpt::config::CConfigFileMemory ini;
  p.saveToConfigFile(ini, "rawlog");
  EXPECT_NEAR(ini.read_double("rawlog", "yaw_deg", 0), 90.0, 1e-9);  // unit suffix on disk
  RawlogWriter::Params q;
  q.loadFromConfigFile(ini, "rawlog");
  EXPECT_EQ(q.sensor_label, "VLP16_ROOF");
  EXPECT_EQ(q.model, "HDL32");
  EXPECT_DOUBLE_EQ(q.min_range_m, 0.5);
  EXPECT_DOUBLE_EQ(q.z_m, 1.73);
  EXPECT_NEAR(q.yaw_rad, M_PI / 2, 1e-12);
  ini.write("rawlog", "min_range_m", std::string("near"));
  EXPECT_THROW(q.loadFromConfigFile(ini, "rawlog"), std::runtime_error);
}

TEST(Rawlog, SensorPoseAndRangesReachTheObservation) {
  RawlogWriter::Params p;
  p.z_m = 1.73;
  p.yaw_rad = M_PI / 2;
  p.max_range_m = 100.0;
  const fs::path path = tempDir() / "pose.rawlog";
  {
    RawlogWriter w(path.string(), p);
    w.writeSweep(makeRecording(1, 4).sweeps[0]);
    w.close();
  }
  mrpt::obs::CRawlog rawlog;
  ASSERT_TRUE(rawlog.loadFromRawLogFile(path.string()));
  auto v = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(rawlog.getAsObservation(0));
  ASSERT_TRUE(v);
  EXPECT_NEAR(v->sensorPose.z(), 1.73, 1e-12);
  EXPECT_NEAR(v->sensorPose.yaw(), M_PI / 2, 1e-12);
  EXPECT_DOUBLE_EQ(v->maxRange, 100.0);
  fs::remove(path);
}
