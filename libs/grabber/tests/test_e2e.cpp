// End to end on loopback: the simulator streams real-format VLP-16 packets, CAN frames come over a
// socketpair; the rawlog read back must hold every packet, byte for byte, in order.
#include <gtest/gtest.h>
#include <linux/can.h>
#include <linux/can/error.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <set>

#include <mrpt/core/Clock.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/serialization/CArchive.h>

#include "grab_test_util.h"
#include "roadslam/can/candump.h"
#include "roadslam/grabber/grabber.h"
#include "roadslam/pcap/pcap_reader.h"
#include "roadslam/rawlog/rawlog_index.h"
#include "roadslam/sim/outputs.h"
#include "roadslam/velodyne/encoder.h"
#include "roadslam/velodyne/sweep_assembler.h"

using namespace roadslam;
using namespace roadslam::grabber;

namespace {

std::vector<std::vector<uint8_t>> pcapPayloads(const std::string& path, uint16_t port) {
  std::vector<std::vector<uint8_t>> out;
  for (auto& d : pcap::readUdpDatagrams(path, port)) out.push_back(d.payload);
  return out;
}

}  // namespace

class GrabZeroLoss : public ::testing::TestWithParam<double> {};

TEST_P(GrabZeroLoss, EveryPacketAndFrameRecordedInOrder) {
  const double speed = GetParam();
  const auto& pkts = test::simPackets(2.0);
  const auto expected = test::dataPayloads(pkts);
  test::TempDir dir("e2e_" + std::to_string(int(speed)));
  // Segments rotate every 0.5 s: the recording spans several rawlogs and sidecars.
  Grabber g(test::paramsFromText(test::testIni("rotate_period_s = 0.5\n")), dir.str());
  int sv[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, sv), 0);
  g.useCanSocket(sv[0], "can0");
  g.start();
  std::size_t bus_off = 0, can_errors = 0;
  std::thread can_tx([&] { can_errors = test::sendCan(sv[1], 300, &bus_off); });
  std::size_t sent = 0;
  {
    sim::UdpStreamer streamer("127.0.0.1", g.dataPort(0), speed);  // the simulator's own streamer
    for (const auto& p : pkts)
      if (p.port == 2368) streamer.packet(p.capture_s, p.port, p.bytes.data(), p.bytes.size());
    sent = streamer.sent();
  }
  can_tx.join();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  g.stop();
  ::close(sv[1]);
  const GrabStatus st = g.status();

  ASSERT_EQ(sent, expected.size());
  const SensorStatus& s = st.sensors.at(0);
  EXPECT_EQ(s.data_packets, sent);
  EXPECT_EQ(s.missing, 0u);
  EXPECT_EQ(s.kernel_drops, 0u);
  EXPECT_EQ(s.queue_drops, 0u);
  EXPECT_EQ(st.writer.packets, sent);
  EXPECT_EQ(st.writer.write_errors, 0u);

  // Segments concatenate into one readable rawlog (multi-member gzip).
  const auto segments = test::segmentFiles(dir.str(), "grab", ".rawlog");
  EXPECT_GE(segments.size(), 2u);
  EXPECT_EQ(st.writer.segments, segments.size());
  std::string joined;
  for (const auto& f : segments) joined += test::readAll(f);
  std::ofstream(dir.str() + "/all.rawlog", std::ios::binary) << joined;
  std::size_t scans = 0;
  std::string error;
  const auto recorded = test::readRawlog(dir.str() + "/all.rawlog", &scans, &error);
  EXPECT_TRUE(error.empty()) << error;
  EXPECT_TRUE(recorded == expected) << recorded.size() << " of " << expected.size() << " packets";
  // Sweeps: as many observations as the decoder's sweep assembler cuts from the same packets.
  velodyne::SweepAssembler a;
  for (const auto& p : expected) a.addPacket(p.data(), p.size(), 0);
  a.finish();
  // A sender starved for the poll timeout (a loaded test machine) cuts a revolution in two; the
  // grabber counts each such cut.
  EXPECT_EQ(scans, a.stats().sweeps + s.pause_cuts) << s.pause_cuts << " pause cuts";
  EXPECT_EQ(st.writer.sweeps, scans);
  // Lossless sidecar.
  std::vector<std::vector<uint8_t>> sidecar;
  const auto pcaps = test::segmentFiles(dir.str(), "lidar", ".pcap");
  EXPECT_EQ(pcaps.size(), segments.size());
  for (const auto& f : pcaps)
    for (auto& p : pcapPayloads(f, 2368)) sidecar.push_back(std::move(p));
  EXPECT_TRUE(sidecar == expected);

  EXPECT_EQ(st.can.frames, 300u);
  EXPECT_EQ(st.can.error_frames, can_errors);
  EXPECT_EQ(st.can.bus_off, bus_off);
  EXPECT_EQ(st.can.queue_drops + st.can.kernel_drops, 0u);
  std::vector<can::CanFrame> frames;
  for (const auto& f : test::segmentFiles(dir.str(), "can", ".candump.log"))
    for (const auto& fr : can::readCandumpFile(f)) frames.push_back(fr);
  ASSERT_EQ(frames.size(), 300u);
  EXPECT_EQ(frames[5].id, 0x105u);
  EXPECT_EQ(frames[5].data[0], 5);
  EXPECT_TRUE(frames[100].error());

  const auto summary = nlohmann::json::parse(test::readAll(dir.str() + "/summary.json"));
  EXPECT_EQ(summary["packets_received"].get<std::size_t>(), sent);
  EXPECT_EQ(summary["packets_dropped"].get<std::size_t>(), 0u);
  EXPECT_EQ(summary["sweeps"].get<std::size_t>(), scans);
  EXPECT_EQ(summary["can_frames"].get<std::size_t>(), 300u);
  EXPECT_EQ(summary["can_frames_dropped"].get<std::size_t>(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Speeds, GrabZeroLoss, ::testing::Values(1.0, 2.0),
                         [](const auto& info) { return "x" + std::to_string(int(info.param)); });

// Malformed payloads and a second sensor on the same port are counted; recording goes on.
TEST(GrabBadInput, MalformedAndForeignPacketsCountedRecordingGoesOn) {
  const auto& pkts = test::simPackets(1.2);
  test::TempDir dir("bad");
  Grabber g(test::paramsFromText(test::testIni("", "source_filter = 127.0.0.1\n")), dir.str());
  g.start();
  const uint16_t dport = g.dataPort(0), pport = g.positionPort(0);
  std::thread intruder([&] {
    std::vector<test::SimPacket> other(pkts.begin(), pkts.begin() + 100);
    for (auto& p : other) p.port = 2368;
    test::sendPaced(other, dport, pport, 1.0, "127.0.0.2");  // a second sensor, same port
  });
  std::vector<test::SimPacket> junk;
  for (int i = 0; i < 20; ++i) junk.push_back({pkts[std::size_t(i)].capture_s, 2368, std::vector<uint8_t>(100 + i, 0xAB)});
  for (int i = 0; i < 10; ++i) junk.push_back({pkts[std::size_t(i)].capture_s, 2368, std::vector<uint8_t>(1206, 0)});
  test::sendPaced(junk, dport, pport, 1.0);
  const std::size_t sent = test::sendPaced(pkts, dport, pport, 2.0);
  intruder.join();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  g.stop();
  const GrabStatus st = g.status();
  ASSERT_EQ(sent, pkts.size());
  const SensorStatus& s = st.sensors.at(0);
  EXPECT_EQ(s.foreign, 100u);
  EXPECT_EQ(s.malformed, 30u);  // 20 of a wrong size, 10 of the right size without block flags
  EXPECT_EQ(s.missing, 0u);
  std::size_t positions = 0;
  for (const auto& p : pkts) positions += p.port == 8308;
  EXPECT_GE(positions, 1u);
  EXPECT_EQ(s.position_packets, positions);
  EXPECT_EQ(st.writer.gps, positions);  // $GPRMC -> CObservationGPS
  EXPECT_TRUE(test::readRawlog(dir.str() + "/grab_000.rawlog") == test::dataPayloads(pkts));
}


// A sender that pauses mid-revolution for longer than the poll timeout: the sweep in progress is
// handed over (written in time order, safe from a crash), the cut is counted, no packet is lost.
TEST(GrabPause, ASweepCutByASenderPauseIsCounted) {
  const auto& pkts = test::simPackets(1.2);
  std::vector<test::SimPacket> data;
  for (const auto& p : pkts)
    if (p.port == 2368) data.push_back(p);
  velodyne::SweepAssembler a;
  for (const auto& p : data) a.addPacket(p.bytes.data(), p.bytes.size(), 0);
  a.finish();
  test::TempDir dir("pause");
  Grabber g(test::paramsFromText(test::testIni("")), dir.str());
  g.start();
  const uint16_t dport = g.dataPort(0), pport = g.positionPort(0);
  const std::size_t half = data.size() / 2;  // inside a revolution: 75 packets make one at 10 Hz
  std::size_t sent = test::sendPaced({data.begin(), data.begin() + long(half)}, dport, pport, 4.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(400));  // poll timeout 100 ms
  sent += test::sendPaced({data.begin() + long(half), data.end()}, dport, pport, 4.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  g.stop();
  const GrabStatus st = g.status();
  ASSERT_EQ(sent, data.size());
  EXPECT_GE(st.sensors.at(0).pause_cuts, 1u);
  std::size_t scans = 0;
  EXPECT_TRUE(test::readRawlog(dir.str() + "/grab_000.rawlog", &scans) == test::dataPayloads(data));
  EXPECT_EQ(scans, a.stats().sweeps + st.sensors.at(0).pause_cuts);
  const auto summary = nlohmann::json::parse(test::readAll(dir.str() + "/summary.json"));
  EXPECT_EQ(summary["sensors"][0]["pause_cuts"].get<std::size_t>(), st.sensors.at(0).pause_cuts);
}

// A writer that cannot keep up (queue of one item, a burst of position packets sent unpaced):
// the receiver never blocks, the overflow is counted, and written + dropped = received.
TEST(GrabOverflow, FullQueueDropsAreCountedNeverBlock) {
  const auto& pkts = test::simPackets(1.2);
  std::vector<test::SimPacket> burst;
  for (const auto& p : pkts)
    if (p.port == 8308) burst.push_back(p);
  ASSERT_FALSE(burst.empty());
  while (burst.size() < 20000) burst.push_back(burst[burst.size() % 2]);
  test::TempDir dir("overflow");
  Grabber g(test::paramsFromText(test::testIni("queue_capacity = 1\n")), dir.str());
  g.start();
  const std::size_t sent = test::sendPaced(burst, g.dataPort(0), g.positionPort(0), 1e9);  // unpaced
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  g.stop();
  const GrabStatus st = g.status();
  const SensorStatus& s = st.sensors.at(0);
  EXPECT_EQ(s.position_packets + s.kernel_drops, sent);
  EXPECT_GT(s.queue_drops, 0u);
  EXPECT_EQ(s.queue_high_water, 1u);  // the capacity
  EXPECT_EQ(st.writer.gps + s.queue_drops, s.position_packets);
  const auto summary = nlohmann::json::parse(test::readAll(dir.str() + "/summary.json"));
  EXPECT_GE(summary["packets_dropped"].get<std::size_t>(), s.queue_drops);
  RecordProperty("queue_drops", int(s.queue_drops));
}

// Two VLP-16s, each on its own ports with its own label and mounting pose: both recorded in full,
// observations in time order.
TEST(GrabTwoSensors, EachSensorRecordedWithItsLabelAndPoseInTimeOrder) {
  const auto& pkts = test::simPackets(1.2);
  const auto expected = test::dataPayloads(pkts);
  test::TempDir dir("two");
  const std::string ini =
      "[grab]\nsensors = front, rear\n"
      "[front]\ndata_port = 0\nposition_port = 0\nsensor_label = FRONT\nx_m = 1.2\nz_m = 1.6\n"
      "[rear]\ndata_port = 0\nposition_port = 0\nsensor_label = REAR\nx_m = -0.8\nz_m = 1.5\nyaw_deg = 180\n";
  Grabber g(test::paramsFromText(ini), dir.str());
  g.start();
  std::thread rear([&] { test::sendPaced(pkts, g.dataPort(1), g.positionPort(1), 1.0); });
  test::sendPaced(pkts, g.dataPort(0), g.positionPort(0), 1.0);
  rear.join();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  g.stop();
  EXPECT_EQ(g.status().writer.late, 0u);

  std::map<std::string, std::vector<std::vector<uint8_t>>> by_label;
  std::map<std::string, mrpt::poses::CPose3D> pose;
  double last_t = 0;
  std::size_t out_of_order = 0;
  mrpt::io::CFileGZInputStream in(dir.str() + "/grab_000.rawlog");
  auto ar = mrpt::serialization::archiveFrom(in);
  for (;;) {
    mrpt::serialization::CSerializable::Ptr obj;
    try {
      obj = ar.ReadObject();
    } catch (const std::exception&) {
      break;  // end of the stream
    }
    auto o = std::dynamic_pointer_cast<mrpt::obs::CObservation>(obj);
    ASSERT_TRUE(o);
    const double t = mrpt::Clock::toDouble(o->timestamp);
    out_of_order += t < last_t;
    last_t = t;
    auto v = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(obj);
    if (!v) continue;
    pose[v->sensorLabel] = v->sensorPose;
    for (const auto& p : v->scan_packets) {
      const auto* b = reinterpret_cast<const uint8_t*>(&p);
      by_label[v->sensorLabel].emplace_back(b, b + sizeof(p));
    }
  }
  EXPECT_EQ(out_of_order, 0u);
  ASSERT_EQ(by_label.size(), 2u);
  EXPECT_TRUE(by_label["FRONT"] == expected);
  EXPECT_TRUE(by_label["REAR"] == expected);
  EXPECT_NEAR(pose["FRONT"].x(), 1.2, 1e-9);
  EXPECT_NEAR(pose["REAR"].x(), -0.8, 1e-9);
  EXPECT_NEAR(std::abs(pose["REAR"].yaw()), M_PI, 1e-9);
  EXPECT_TRUE(std::filesystem::exists(dir.str() + "/front_000.pcap"));
  EXPECT_TRUE(std::filesystem::exists(dir.str() + "/rear_000.pcap"));
}

// Disk full (the rawlog and the pcap sidecar are links to /dev/full: every write fails with
// ENOSPC): write errors are counted and reported, the receivers go on, stop() returns.
TEST(GrabDiskFull, WriteErrorsCountedRecordingGoesOn) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  const auto& pkts = test::simPackets(1.2);
  test::TempDir dir("full");
  std::filesystem::create_symlink("/dev/full", dir.path / "grab_000.rawlog");
  std::filesystem::create_symlink("/dev/full", dir.path / "lidar_000.pcap");
  Grabber g(test::paramsFromText(test::testIni()), dir.str());
  g.start();
  const std::size_t sent = test::sendPaced(pkts, g.dataPort(0), g.positionPort(0), 2.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  g.stop();
  const GrabStatus st = g.status();
  EXPECT_EQ(st.sensors[0].packets, sent);
  EXPECT_GT(st.writer.write_errors, 0u);
  EXPECT_FALSE(st.writer.error.empty());
  EXPECT_NE(Grabber::formatStatus(st).find("WRITE ERRORS"), std::string::npos);
  const auto summary = nlohmann::json::parse(test::readAll(dir.str() + "/summary.json"));
  EXPECT_GT(summary["write_errors"].get<std::size_t>(), 0u);
  EXPECT_EQ(summary["packets_received"].get<std::size_t>(), sent);
}

// Without source_filter the first sender is locked: a second sensor that starts later on the same
// port is counted as foreign and kept out of the sweeps (and out of the gap count).
TEST(GrabBadInput, SecondSenderOnTheSamePortLockedOut) {
  const auto& pkts = test::simPackets(1.2);
  test::TempDir dir("lock");
  Grabber g(test::paramsFromText(test::testIni()), dir.str());
  g.start();
  const uint16_t dport = g.dataPort(0), pport = g.positionPort(0);
  std::thread intruder([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    std::vector<test::SimPacket> other(pkts.begin() + 500, pkts.begin() + 600);
    test::sendPaced(other, dport, pport, 1.0, "127.0.0.2");
  });
  const std::size_t sent = test::sendPaced(pkts, dport, pport, 1.0);
  intruder.join();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  g.stop();
  const SensorStatus s = g.status().sensors.at(0);
  EXPECT_EQ(s.packets, sent + 100);
  EXPECT_EQ(s.foreign, 100u);
  EXPECT_EQ(s.missing, 0u);
  EXPECT_TRUE(test::readRawlog(dir.str() + "/grab_000.rawlog") == test::dataPayloads(pkts));
}

// Monitoring (roadslam-view --udp): no out folder, nothing written; the tap receives every sweep
// with the same packets the recorder would have written, in time order. Oracle: the sweep
// assembler over the simulator's packets, and the packets themselves.
TEST(GrabMonitor, TapReceivesEverySweepAndNothingIsWritten) {
  const auto& pkts = test::simPackets(1.0);
  const auto expected = test::dataPayloads(pkts);
  test::TempDir cwd("monitor");
  const auto before = std::filesystem::current_path();
  std::filesystem::current_path(cwd.path);  // a stray relative write would land here
  std::vector<std::shared_ptr<mrpt::obs::CObservation>> tapped;
  std::mutex m;
  {
    Grabber g(test::paramsFromText(test::testIni()), "");
    g.setObservationTap([&](const std::shared_ptr<mrpt::obs::CObservation>& o) {
      std::lock_guard<std::mutex> lock(m);
      tapped.push_back(o);
    });
    g.start();
    {
      sim::UdpStreamer streamer("127.0.0.1", g.dataPort(0), 4.0);
      for (const auto& p : pkts)
        if (p.port == 2368) streamer.packet(p.capture_s, p.port, p.bytes.data(), p.bytes.size());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    g.stop();
    EXPECT_EQ(g.status().writer.segments, 0u);
    EXPECT_THROW(g.setObservationTap({}), std::logic_error);
  }
  std::filesystem::current_path(before);
  EXPECT_TRUE(std::filesystem::is_empty(cwd.path)) << "monitoring wrote a file";
  std::vector<std::vector<uint8_t>> got;
  double last = -1;
  for (const auto& o : tapped) {
    const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(o);
    ASSERT_TRUE(scan) << o->GetRuntimeClass()->className;
    const double t = mrpt::Clock::toDouble(scan->timestamp);
    EXPECT_GE(t, last);
    last = t;
    for (const auto& p : scan->scan_packets) {
      const auto* b = reinterpret_cast<const uint8_t*>(&p);
      got.emplace_back(b, b + velodyne::kDataPacketSize);
    }
  }
  velodyne::SweepAssembler a;
  for (const auto& p : expected) a.addPacket(p.data(), p.size(), 0);
  a.finish();
  EXPECT_EQ(tapped.size(), a.stats().sweeps);
  EXPECT_TRUE(got == expected) << got.size() << " of " << expected.size() << " packets";
}

// Every closed segment carries its index sidecar, so its first open reads no more than the
// sidecar. Oracle: the index RawlogIndex builds by reading the segment itself; observations loaded
// through the grabber's access points equal those loaded through the built index's.
TEST(GrabIndex, EachClosedSegmentCarriesItsIndex) {
  const auto& pkts = test::simPackets(2.0);
  test::TempDir dir("index");
  Grabber g(test::paramsFromText(test::testIni("rotate_period_s = 0.7\nflush_period_ms = 100\n")), dir.str());
  g.start();
  {
    sim::UdpStreamer streamer("127.0.0.1", g.dataPort(0), 2.0);
    for (const auto& p : pkts)
      if (p.port == 2368) streamer.packet(p.capture_s, p.port, p.bytes.data(), p.bytes.size());
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  g.stop();
  const auto segments = test::segmentFiles(dir.str(), "grab", ".rawlog");
  ASSERT_GE(segments.size(), 2u);
  std::size_t points = 0, observations = 0;
  for (const auto& seg : segments) {
    ASSERT_TRUE(std::filesystem::exists(rawlog::RawlogIndex::sidecarPath(seg))) << seg;
    const auto cached = rawlog::RawlogIndex::open(seg);
    EXPECT_TRUE(cached->openInfo().from_cache) << seg << ": " << cached->openInfo().cache_note;
    rawlog::RawlogIndexOptions read;
    read.use_cache = read.write_cache = false;
    read.span_bytes = 1u << 20;
    const auto built = rawlog::RawlogIndex::open(seg, read);
    ASSERT_EQ(cached->size(), built->size()) << seg;
    EXPECT_TRUE(cached->complete());
    EXPECT_EQ(cached->uncompressedBytes(), built->uncompressedBytes());
    for (std::size_t i = 0; i < built->size(); ++i) {
      ASSERT_EQ(cached->entry(i).offset, built->entry(i).offset) << seg << " #" << i;
      ASSERT_EQ(cached->entry(i).size, built->entry(i).size) << seg << " #" << i;
      ASSERT_EQ(cached->entry(i).stamp_s, built->entry(i).stamp_s) << seg << " #" << i;
      ASSERT_EQ(cached->label(i), built->label(i));
      ASSERT_EQ(cached->className(i), built->className(i));
    }
    points += cached->accessPoints();
    observations += built->size();
    for (std::size_t i = built->size(); i-- > 0;) {  // backwards: every load seeks through a point
      const auto a = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(cached->load(i));
      const auto b = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(built->load(i));
      ASSERT_TRUE(a && b) << seg << " #" << i;
      ASSERT_EQ(a->scan_packets.size(), b->scan_packets.size());
      ASSERT_EQ(0, std::memcmp(a->scan_packets.data(), b->scan_packets.data(),
                               a->scan_packets.size() * sizeof(a->scan_packets[0])))
          << seg << " #" << i;
    }
  }
  EXPECT_EQ(observations, g.status().writer.observations);
  EXPECT_GT(points, 0u) << "access points at the sync flushes (every 4 MB of data)";
}

namespace {

/// \p n packets of an HDL-32E turning at 10 Hz (a block every 46.08 us, HDL-32E manual appendix E):
/// ranges by laser, so channels k and k+16 differ as two lasers do.
std::vector<test::SimPacket> hdl32Packets(int n) {
  std::vector<test::SimPacket> out;
  for (int k = 0; k < n; ++k) {
    std::array<velodyne::Hdl32Firing, velodyne::kBlocksPerPacket> f{};
    const double t_pkt = k * velodyne::kBlocksPerPacket * velodyne::kHdl32BlockPeriod_s;
    for (int b = 0; b < velodyne::kBlocksPerPacket; ++b) {
      f[b].azimuth_deg = std::fmod(3600.0 * (t_pkt + b * velodyne::kHdl32BlockPeriod_s), 360.0);
      for (int c = 0; c < velodyne::kHdl32Lasers; ++c) f[b].returns[c] = {3.0f + 0.5f * float(c), 50};
    }
    const auto bytes = velodyne::encodeHdl32Packet(f, 1000000u + uint32_t(std::lround(t_pkt * 1e6)));
    out.push_back({t_pkt, 2368, std::vector<uint8_t>(bytes.begin(), bytes.end())});
  }
  return out;
}

/// Laser counts of the calibrations stored with the sweeps of \p rawlog.
std::set<std::size_t> calibrationLasers(const std::string& rawlog) {
  std::set<std::size_t> out;
  mrpt::io::CFileGZInputStream in(rawlog);
  auto ar = mrpt::serialization::archiveFrom(in);
  for (;;) {
    mrpt::serialization::CSerializable::Ptr rec;
    try {
      rec = ar.ReadObject();
    } catch (const std::exception&) {
      break;
    }
    if (auto v = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(rec))
      out.insert(v->calibration.laser_corrections.size());
  }
  return out;
}

/// A grabber on model = auto fed \p pkts; its summary.json's first sensor and the final status.
std::pair<nlohmann::json, GrabStatus> grabAuto(const std::vector<test::SimPacket>& pkts, const std::string& dir) {
  const std::string ini = "[grab]\nsensors = lidar\nflush_period_ms = 200\nstatus_period_ms = 200\n"
                          "[lidar]\ndata_port = 0\nposition_port = 0\nmodel = auto\nsensor_label = LIDAR\n";
  Grabber g(test::paramsFromText(ini), dir);
  g.start();
  test::sendPaced(pkts, g.dataPort(0), g.positionPort(0), 4.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  g.stop();
  GrabStatus st = g.status();
  g.writeSummary(st);
  return {nlohmann::json::parse(test::readAll(dir + "/summary.json"))["sensors"][0], st};
}

}  // namespace

// model = auto: each sensor's model comes from its packets (velodyne/model_choice.h), is named in
// summary.json, and chooses the calibration stored with its sweeps.
TEST(GrabModel, AnHdl32OnAutoIsRecordedWithTheHdl32Calibration) {
  test::TempDir dir("model_hdl32");
  const auto [sensor, st] = grabAuto(hdl32Packets(300), dir.str());
  EXPECT_EQ(sensor["lidar_model"], "HDL-32E");
  EXPECT_EQ(sensor["lidar_model_source"], "product byte");
  EXPECT_EQ(sensor["lidar_layout"].get<std::string>().rfind("HDL-32E layout (46.", 0), 0u) << sensor;
  EXPECT_EQ(calibrationLasers(dir.str() + "/grab_000.rawlog"), std::set<std::size_t>{32});
}

TEST(GrabModel, AVlp16WithTheHdl32ByteIsAVlp16ByItsLayoutWithAWarning) {
  std::vector<test::SimPacket> data;
  for (const auto& p : test::simPackets(1.2))
    if (p.port == 2368) data.push_back(p), data.back().bytes[velodyne::kProductIdOffset] = 0x21;
  test::TempDir dir("model_lying_byte");
  const auto [sensor, st] = grabAuto(data, dir.str());
  EXPECT_EQ(sensor["lidar_model"], "VLP-16");
  EXPECT_EQ(sensor["lidar_model_source"], "packet layout");
  std::string events;
  for (const auto& e : st.events) events += e + "\n";
  EXPECT_NE(events.find("LIDAR: warning: packets have the VLP-16 layout (110.6 us per block) but product byte 0x21 "
                        "says HDL-32E; decoding as VLP-16; set [lidar] model = hdl32 to force"),
            std::string::npos)
      << events;
  EXPECT_EQ(calibrationLasers(dir.str() + "/grab_000.rawlog"), std::set<std::size_t>{16});
}
