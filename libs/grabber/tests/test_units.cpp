// Unit and oracle tests of the grabber's parts: queue, sweep grouping (against the velodyne
// SweepAssembler), crash-safe gzip segments, ini loading (the shipped ini/grab.ini).
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>

#include "grab_test_util.h"
#include "roadslam/grabber/bounded_queue.h"
#include "roadslam/grabber/segment_writer.h"
#include "roadslam/grabber/sweep_grouper.h"
#include "roadslam/velodyne/sweep_assembler.h"

using namespace roadslam;
using namespace roadslam::grabber;

TEST(BoundedQueue, RefusesWhenFullAndKeepsOrder) {
  BoundedQueue<int> q(3);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(q.tryPush(int(i)));
  EXPECT_FALSE(q.tryPush(99));
  EXPECT_EQ(q.size(), 3u);
  int v = -1;
  ASSERT_TRUE(q.tryPop(v));
  EXPECT_EQ(v, 0);
  EXPECT_TRUE(q.tryPush(3));
  std::vector<int> rest;
  while (q.tryPop(v)) rest.push_back(v);
  EXPECT_EQ(rest, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(q.highWater(), 3u);
}

// Oracle: the decoder's SweepAssembler (per-block cut at azimuth 0) on the same packets.
TEST(SweepGrouper, SameSweepCountAsSweepAssembler) {
  const auto& pkts = test::simPackets(1.0);
  SweepGrouper g;
  velodyne::SweepAssembler a;
  std::vector<std::vector<uint8_t>> regrouped;
  std::size_t sweeps = 0, data = 0;
  for (const auto& p : pkts) {
    if (p.port != 2368) continue;
    ++data;
    a.addPacket(p.bytes.data(), p.bytes.size(), p.capture_s);
    velodyne::RawPacket rp;
    rp.payload = p.bytes;
    if (g.add(std::move(rp))) {
      ++sweeps;
      for (auto& q : g.take()) regrouped.push_back(q.payload);
    }
  }
  a.finish();
  auto last = g.takePartial();
  if (!last.empty()) ++sweeps;
  for (auto& q : last) regrouped.push_back(q.payload);
  EXPECT_GT(sweeps, 8u);  // 1 s at 10 Hz
  EXPECT_EQ(sweeps, a.stats().sweeps);
  EXPECT_EQ(regrouped, test::dataPayloads(pkts));  // nothing lost, nothing reordered
  EXPECT_EQ(regrouped.size(), data);
}

// takePartial() in the middle of a revolution (the sensor thread's poll timeout) cuts it in two when
// the packets after it go on with it; at a revolution's end, or at the end of the stream, nothing is cut.
TEST(SweepGrouper, CountsTheRevolutionsAPartialHandOverCuts) {
  const auto& pkts = test::simPackets(1.0);
  std::vector<std::vector<uint8_t>> data;
  for (const auto& p : pkts)
    if (p.port == 2368) data.push_back(p.bytes);
  auto feed = [](SweepGrouper& g, const std::vector<uint8_t>& bytes) {
    velodyne::RawPacket rp;
    rp.payload = bytes;
    return g.add(std::move(rp));
  };
  SweepGrouper g;
  std::size_t sweeps = 0;
  bool handed_over = false;
  for (const auto& d : data) {
    if (!feed(g, d)) continue;
    ++sweeps;
    g.take();
    if (!handed_over) {  // right after a revolution's first packet: the rest of it follows, a cut
      sweeps += !g.takePartial().empty();
      handed_over = true;
    }
  }
  sweeps += !g.takePartial().empty();  // the end of the stream: not a cut
  velodyne::SweepAssembler a;
  for (const auto& d : data) a.addPacket(d.data(), d.size(), 0);
  a.finish();
  EXPECT_EQ(g.revolutionsCut(), 1u);
  EXPECT_EQ(sweeps, a.stats().sweeps + 1);
}

TEST(SweepGrouper, RejectsMalformedPackets) {
  SweepGrouper g;
  velodyne::RawPacket shortp;
  shortp.payload.assign(100, 0xEE);
  EXPECT_FALSE(g.add(std::move(shortp)));
  velodyne::RawPacket noflag;
  noflag.payload.assign(1206, 0);
  EXPECT_FALSE(g.add(std::move(noflag)));
  EXPECT_EQ(g.pending(), 0u);
}

namespace {
mrpt::obs::CObservationOdometry odo(int i) {
  mrpt::obs::CObservationOdometry o;
  o.sensorLabel = "T";
  o.odometry = mrpt::poses::CPose2D(i, 0, 0);
  return o;
}

/// odometry.x of every object until the end or the first undecodable one.
std::vector<int> readTicks(const std::string& path) {
  std::vector<int> out;
  mrpt::io::CFileGZInputStream in(path);
  auto ar = mrpt::serialization::archiveFrom(in);
  try {
    for (;;) {
      auto obj = ar.ReadObject();
      auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obj);
      if (!o) break;
      out.push_back(int(std::lround(o->odometry.x())));
    }
  } catch (const std::exception&) {
  }
  return out;
}
}  // namespace

// What a reader sees after a SIGKILL: the file as it is on disk while the writer still runs.
TEST(SegmentWriter, SyncFlushedObjectsSurviveAHardKill) {
  test::TempDir dir("seg_kill");
  SegmentWriter w(dir.str(), "k", SegmentPolicy{});
  for (int i = 0; i < 200; ++i) w.write(odo(i), 0);
  w.syncFlush();
  for (int i = 200; i < 210; ++i) w.write(odo(i), 0);  // still in zlib's buffer
  const std::string snapshot = dir.str() + "/snapshot.rawlog";
  std::filesystem::copy_file(w.segments().front(), snapshot);
  const auto got = readTicks(snapshot);
  ASSERT_GE(got.size(), 200u);
  for (int i = 0; i < int(got.size()); ++i) ASSERT_EQ(got[std::size_t(i)], i);
  // And the reader of the repo sees the same prefix with an error message, not a crash.
  w.close();
  EXPECT_EQ(readTicks(w.segments().front()).size(), 210u);
}

TEST(SegmentWriter, RotatesBySizeAndSegmentsConcatenate) {
  test::TempDir dir("seg_rot");
  SegmentPolicy pol;
  pol.max_size_bytes = 4000;
  pol.compression_level = 0;  // stored: the size grows with every object
  SegmentWriter w(dir.str(), "r", pol);
  for (int i = 0; i < 300; ++i) {
    w.write(odo(i), 0);
    if (i % 10 == 9) w.syncFlush();  // the size is known at flushes
  }
  w.close();
  ASSERT_GE(w.segments().size(), 3u);
  std::string all;
  std::vector<int> joined;
  for (const auto& s : w.segments()) {
    const auto t = readTicks(s);
    EXPECT_FALSE(t.empty()) << s;
    joined.insert(joined.end(), t.begin(), t.end());
    all += test::readAll(s);
  }
  ASSERT_EQ(joined.size(), 300u);
  for (int i = 0; i < 300; ++i) EXPECT_EQ(joined[std::size_t(i)], i);
  const std::string cat = dir.str() + "/all.rawlog";
  std::ofstream(cat, std::ios::binary) << all;
  EXPECT_EQ(readTicks(cat).size(), 300u);  // multi-member gzip
}

TEST(SegmentWriter, RotatesByAge) {
  test::TempDir dir("seg_age");
  SegmentPolicy pol;
  pol.max_age_s = 1.0;
  SegmentWriter w(dir.str(), "a", pol);
  for (int i = 0; i < 30; ++i) w.write(odo(i), 0.25 * i);  // 7.25 s of writes
  w.close();
  EXPECT_EQ(w.segments().size(), 8u);
}

TEST(GrabParams, ShippedIniLoads) {
  const std::string ini = std::string(ROADSLAM_SOURCE_DIR) + "/ini/grab.ini";
  const GrabParams p = GrabParams::fromFile(ini);
  ASSERT_EQ(p.sensors.size(), 1u);
  EXPECT_EQ(p.sensors[0].udp.ports.data_port, 2368);
  EXPECT_EQ(p.sensors[0].udp.ports.position_port, 8308);
  EXPECT_EQ(p.sensors[0].scan.sensor_label, "VELODYNE_TOP");
  EXPECT_DOUBLE_EQ(p.sensors[0].scan.z_m, 1.9);
  EXPECT_EQ(p.can.source, CanParams::Source::SocketCan);
  EXPECT_EQ(p.can.socketcan.interface, "can0");
  EXPECT_TRUE(std::filesystem::exists(p.can.vehicle_ini)) << p.can.vehicle_ini;
  EXPECT_DOUBLE_EQ(p.writer.flush_period_s, 0.5);
  EXPECT_DOUBLE_EQ(p.writer.rotate_size_bytes, 512e6);
  EXPECT_EQ(p.gnss.source, GnssParams::Source::Gpsd);
  EXPECT_EQ(p.gnss.gpsd_port, 2947);
  EXPECT_DOUBLE_EQ(p.gnss.epoch_idle_s, 0.1);
  // Round trip through saveToConfigFile.
  mrpt::config::CConfigFileMemory cfg;
  p.saveToConfigFile(cfg);
  GrabParams q;
  q.loadFromConfigFile(cfg);
  EXPECT_EQ(q.sensors[0].udp.ports.data_port, 2368);
  EXPECT_NEAR(q.sensors[0].scan.yaw_rad, p.sensors[0].scan.yaw_rad, 1e-12);
  EXPECT_DOUBLE_EQ(q.writer.reorder_window_s, p.writer.reorder_window_s);
  EXPECT_EQ(q.can.vehicle_ini, p.can.vehicle_ini);
  EXPECT_EQ(q.gnss.source, p.gnss.source);
  EXPECT_DOUBLE_EQ(q.gnss.silent_after_s, p.gnss.silent_after_s);
}

TEST(GrabParams, ErrorsNameTheKey) {
  try {
    test::paramsFromText(test::testIni("speling = 1"));
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("speling"), std::string::npos) << e.what();
  }
  try {
    test::paramsFromText("[grab]\nsensors = a,b\n[a]\ndata_port = 3000\n[b]\ndata_port = 3000\n");
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("already used by [a]"), std::string::npos) << e.what();
  }
  try {
    test::paramsFromText(test::testIni("can = c\n[c]\nsource = candump\n"));
    FAIL();
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("candump_file"), std::string::npos) << e.what();
  }
}

TEST(GrabParams, ShippedSimIniLoads) {
  const GrabParams p = GrabParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/grab-sim.ini");
  ASSERT_EQ(p.sensors.size(), 1u);
  EXPECT_EQ(p.sensors[0].udp.ports.data_port, 2368);
  EXPECT_EQ(p.sensors[0].udp.source_filter, "127.0.0.1");
  EXPECT_EQ(p.can.source, CanParams::Source::Candump);
  EXPECT_TRUE(p.can.restamp);
  EXPECT_TRUE(std::filesystem::exists(p.can.vehicle_ini)) << p.can.vehicle_ini;
  // The candump path resolves into the shared data folder, relative to the ini.
  EXPECT_EQ(std::filesystem::weakly_canonical(p.can.candump_file),
            std::filesystem::weakly_canonical(std::string(ROADSLAM_SHARED_DATA) +
                                              "/can/rav4-2017/rav4_2018-08-02_seg40.candump.log"));
}
