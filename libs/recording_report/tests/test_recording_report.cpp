// The recording report on real files against independent oracles: a simulated drive whose rates are set
// by the sensor's timing (VLP-16 manual: 1327.104 us per packet, 10 Hz turns) and by the simulator's CAN
// schedule (libs/sim/src/can_output.cpp: 10 ms steps, ids every 1, 1, 2, 2, 10 steps), a copy of it with
// half a second of packets cut out, its rawlog conversion, damaged copies, the dead-reckoned length
// against the simulator's ground truth, the real MRPT and VeloView captures and the real Civic CAN log
// (counts from their MANIFESTs), and the page rendered in headless Chromium.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/serialization/CArchive.h>

#include "roadslam/runfolder/run_folder.h"
#include "roadslam/pcap/pcap_writer.h"
#include "roadslam/recording_report/recording_report.h"
#include "roadslam/sim/outputs.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/sources/pcap_source.h"

namespace fs = std::filesystem;
namespace rr = roadslam::recording_report;
namespace sim = roadslam::sim;

namespace {

const std::string kSrc = ROADSLAM_SOURCE_DIR;
const std::string kBin = std::string(ROADSLAM_BINARY_DIR) + "/bin";
const std::string kData = ROADSLAM_SHARED_DATA;
constexpr double kVlp16PacketRate = 1.0 / 1327.104e-6;  // 753.5 /s (VLP-16 manual 9.5)
constexpr double kCutFrom_s = 2.0, kCutTo_s = 2.5;      // the hole cut into the copy, since the first packet

/// 5 s of the urban loop, simulated once per build tree (velodyne.pcap, can.log, gt_trajectory.tum).
const std::string& drive() {
  static const std::string dir = [] {
    auto p = sim::ScenarioParams::fromFile(kSrc + "/ini/sim/urban-loop.ini");
    p.duration_s = 5.0;
    return sim::simulateCached(p, ROADSLAM_SIM_CACHE);
  }();
  return dir;
}

std::string freshDir(const std::string& name) {
  const std::string d = std::string(ROADSLAM_BINARY_DIR) + "/test_data/recording_report_" + name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// A copy of the drive's pcap without the data packets in [kCutFrom_s, kCutTo_s) after the first one.
std::string cutPcap(const std::string& dir, size_t* removed) {
  roadslam::sources::PcapPacketSource in(drive() + "/velodyne.pcap");
  const std::string out = dir + "/cut.pcap";
  roadslam::pcap::PcapWriter w(out);
  double t0 = -1;
  *removed = 0;
  while (auto p = in.next()) {
    if (t0 < 0) t0 = p->stamp_s;
    const bool data = p->payload.size() == 1206;
    if (data && p->stamp_s - t0 >= kCutFrom_s && p->stamp_s - t0 < kCutTo_s) {
      ++*removed;
      continue;
    }
    w.writeUdp(p->stamp_s, p->dst_port, p->dst_port, p->payload.data(), p->payload.size(), p->src_ip);
  }
  w.close();
  return out;
}

const rr::StreamStats* stream(const rr::RecordingReport& r, const std::string& kind) {
  for (const auto& s : r.streams)
    if (s.kind == kind) return &s;
  return nullptr;
}

double tumLength(const std::string& path) {
  std::ifstream in(path);
  double len = 0, px = 0, py = 0;
  bool first = true;
  for (std::string line; std::getline(in, line);) {
    std::istringstream ls(line);
    double t, x, y;
    if (!(ls >> t >> x >> y)) continue;
    if (!first) len += std::hypot(x - px, y - py);
    px = x, py = y, first = false;
  }
  return len;
}

rr::ReportInputs simInputs(const std::string& recording) {
  rr::ReportInputs in;
  in.recording = recording;
  in.can_log = drive() + "/can.log";
  in.vehicle_ini = kSrc + "/ini/vehicles/roadslam-sim.ini";
  return in;
}

}  // namespace

TEST(RecordingReport, SimulatedDriveGivesTheSensorsRatesAndCanSchedule) {
  const auto r = rr::buildReport(simInputs(drive() + "/velodyne.pcap"));
  EXPECT_EQ(r.format, "pcap");
  const auto* lidar = stream(r, "lidar");
  ASSERT_NE(lidar, nullptr);
  EXPECT_EQ(lidar->model, "vlp16");
  EXPECT_NEAR(lidar->rate_hz, kVlp16PacketRate, 1.0);
  EXPECT_NEAR(lidar->sweep_rate_hz, 10.0, 0.05);
  EXPECT_NEAR(static_cast<double>(lidar->sweeps), 48, 1) << "5 s at 10 Hz, whole turns between wraps";
  EXPECT_EQ(lidar->gap_count, 0u);
  EXPECT_EQ(lidar->drops, 0u);
  for (double v : lidar->bin_rate_hz) EXPECT_NEAR(v, kVlp16PacketRate, 2.0);
  ASSERT_NE(stream(r, "gps"), nullptr) << "the simulator's position packets";
  EXPECT_NEAR(stream(r, "gps")->rate_hz, 1.0, 0.01);
  ASSERT_TRUE(r.can);
  EXPECT_EQ(r.can->bad_lines, 0u);
  // id -> period in 10 ms steps (can_output.cpp makeStream calls), not read from the DBC
  const std::map<uint32_t, double> hz = {{0x1A0, 100}, {0x130, 100}, {0x1A1, 50}, {0x0C2, 50}, {0x3B0, 10}};
  ASSERT_EQ(r.can->ids.size(), hz.size());
  for (const auto& i : r.can->ids) {
    ASSERT_TRUE(hz.count(i.id)) << i.id;
    EXPECT_NEAR(i.rate_hz, hz.at(i.id), 0.01 * hz.at(i.id)) << i.name;
    EXPECT_EQ(i.gaps, 0u) << i.name;
  }
  EXPECT_NEAR(stream(r, "can")->rate_hz, 310, 1.0) << "the sum of the five";
  ASSERT_EQ(r.can->signals.size(), 3u) << "speed, yaw rate, steering";
  const double gt = tumLength(drive() + "/gt_trajectory.tum");
  ASSERT_GT(gt, 5.0);
  EXPECT_NEAR(r.can->path_length_m, gt, 0.03 * gt) << "dead reckoning against the ground truth path";
  EXPECT_TRUE(r.warnings.empty());
}

TEST(RecordingReport, GnssFixesFollowTheGroundTruth) {
  // the simulator writes its true position as $GPRMC (1 Hz): each fix, east-north about the first, is
  // the ground-truth displacement since the first fix (to the NMEA resolution, 0.0001' ~ 0.2 m)
  rr::ReportInputs in;
  in.recording = drive() + "/velodyne.pcap";
  const auto r = rr::buildReport(in);
  ASSERT_EQ(r.gnss_fixes, 5u);
  std::ifstream gt(drive() + "/gt_trajectory.tum");
  std::vector<std::array<double, 3>> txy;
  for (double t, x, y, z, qx, qy, qz, qw; gt >> t >> x >> y >> z >> qx >> qy >> qz >> qw;) txy.push_back({t, x, y});
  const auto at = [&](double t) {
    return *std::min_element(txy.begin(), txy.end(),
                             [t](const auto& a, const auto& b) { return std::abs(a[0] - t) < std::abs(b[0] - t); });
  };
  const auto g0 = at(r.start_s + r.gnss_t_s[0]);
  for (size_t i = 0; i < r.gnss_x_m.size(); ++i) {
    const auto g = at(r.start_s + r.gnss_t_s[i]);
    EXPECT_NEAR(r.gnss_x_m[i], g[1] - g0[1], 0.3) << i;
    EXPECT_NEAR(r.gnss_y_m[i], g[2] - g0[2], 0.3) << i;
  }
}

TEST(RecordingReport, CutPcapShowsTheGapWhereItWasCutAndTheDropsFromTheSensorClock) {
  const std::string dir = freshDir("cut");
  size_t removed = 0;
  const auto r = rr::buildReport(simInputs(cutPcap(dir, &removed)));
  ASSERT_NEAR(static_cast<double>(removed), 0.5 * kVlp16PacketRate, 2);
  const auto* lidar = stream(r, "lidar");
  ASSERT_NE(lidar, nullptr);
  ASSERT_EQ(lidar->gap_count, 1u);
  ASSERT_EQ(lidar->gaps.size(), 1u);
  const double t0 = lidar->first_s;
  EXPECT_NEAR(lidar->gaps[0].start_s - t0, kCutFrom_s, 2e-3);
  EXPECT_NEAR(lidar->gaps[0].end_s - t0, kCutTo_s, 2e-3);
  EXPECT_EQ(lidar->drops, removed) << "the sensor clock jumps by the packets cut";
  EXPECT_NEAR(lidar->sweep_rate_hz, 10.0, 0.05) << "the turn across the hole is not one";
  EXPECT_NEAR(static_cast<double>(lidar->sweeps), 48 - 6, 1) << "the 5 turns cut and the one across the hole";
  EXPECT_EQ(stream(r, "gps")->gap_count, 0u) << "position packets were kept";
  EXPECT_EQ(stream(r, "can")->gap_count, 0u);
  // the rate over time: the second holding the cut is half full
  EXPECT_NEAR(lidar->bin_rate_hz.at(2), 0.5 * kVlp16PacketRate, 3);
  EXPECT_NEAR(lidar->bin_rate_hz.at(1), kVlp16PacketRate, 2);
  const std::string html = rr::toHtml(r);
  EXPECT_NE(html.find("stroke-dasharray"), std::string::npos) << "the gap marked on the rate plot";
  EXPECT_NE(html.find("<td>2.000</td><td>2.500</td>"), std::string::npos) << "and listed";
}

TEST(RecordingReport, RawlogConversionReportsTheSameSensor) {
  const std::string dir = freshDir("rawlog");
  const std::string rawlog = dir + "/drive.rawlog";
  ASSERT_EQ(std::system((kBin + "/roadslam-rawlog convert " + drive() + "/velodyne.pcap " + rawlog + " > " + dir +
                         "/convert.log 2>&1").c_str()),
            0);
  const auto a = rr::buildReport(simInputs(drive() + "/velodyne.pcap"));
  const auto b = rr::buildReport(simInputs(rawlog));
  EXPECT_EQ(b.format, "rawlog");
  const auto *la = stream(a, "lidar"), *lb = stream(b, "lidar");
  ASSERT_NE(lb, nullptr);
  EXPECT_EQ(lb->count, la->count) << "every packet stored once";
  EXPECT_EQ(lb->sweeps, la->sweeps);
  EXPECT_NEAR(lb->rate_hz, kVlp16PacketRate, 1.0);
  EXPECT_EQ(lb->gap_count, 0u);
  ASSERT_NE(stream(b, "gps"), nullptr) << "CObservationGPS records";
  EXPECT_EQ(stream(b, "gps")->count, stream(a, "gps")->count);
}

TEST(RecordingReport, RawlogLidarsAreToldApartBySensorLabel) {
  // the converted drive rewritten with every other scan labelled LIDAR_B (MRPT's own reader and writer)
  const std::string dir = freshDir("labels");
  const std::string one = dir + "/one.rawlog", two = dir + "/two.rawlog";
  ASSERT_EQ(std::system((kBin + "/roadslam-rawlog convert " + drive() + "/velodyne.pcap " + one + " > /dev/null").c_str()), 0);
  size_t scans = 0;
  {
    mrpt::io::CFileGZInputStream in(one);
    mrpt::io::CFileGZOutputStream out(two);
    auto ar_in = mrpt::serialization::archiveFrom(in);
    auto ar_out = mrpt::serialization::archiveFrom(out);
    for (;;) {
      mrpt::serialization::CSerializable::Ptr o;
      try {
        o = ar_in.ReadObject();
      } catch (const mrpt::serialization::CExceptionEOF&) {
        break;
      }
      if (auto v = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(o))
        v->sensorLabel = scans++ % 2 ? "LIDAR_B" : "LIDAR_A";
      ar_out << *o;
    }
  }
  ASSERT_GT(scans, 40u);
  rr::ReportInputs in;
  in.recording = two;
  const auto r = rr::buildReport(in);
  std::map<std::string, uint64_t> count;
  for (const auto& s : r.streams)
    if (s.kind == "lidar") count[s.label] = s.count;
  ASSERT_EQ(count.size(), 2u);
  EXPECT_EQ(count["velodyne LIDAR_A"] + count["velodyne LIDAR_B"],
            stream(rr::buildReport(simInputs(drive() + "/velodyne.pcap")), "lidar")->count);
}

TEST(RecordingReport, RawlogVehicleObservationsAreStreamsOfTheirOwn) {
  // roadslam-can to-rawlog: a CObservationOdometry per wheel-speed update and a CObservationIMU per
  // yaw-rate update, both sent every 10 ms by the simulator (and GenMsgCycleTime 10 in its DBC)
  const std::string dir = freshDir("vehicle_obs");
  ASSERT_EQ(std::system((kBin + "/roadslam-can to-rawlog --vehicle " + kSrc + "/ini/vehicles/roadslam-sim.ini " + drive() +
                         "/can.log " + dir + "/can.rawlog > /dev/null").c_str()),
            0);
  rr::ReportInputs in;
  in.recording = dir + "/can.rawlog";
  const auto r = rr::buildReport(in);
  std::map<std::string, const rr::StreamStats*> by;
  for (const auto& s : r.streams) by[s.label] = &s;
  ASSERT_EQ(by.size(), 2u);
  ASSERT_TRUE(by.count("CAN_ODOMETRY (CObservationOdometry)"));
  ASSERT_TRUE(by.count("CAN_IMU (CObservationIMU)"));
  for (const auto& [label, s] : by) {
    EXPECT_EQ(s->kind, "rawlog");
    EXPECT_NEAR(s->rate_hz, 100.0, 0.5) << label;
    EXPECT_NEAR(static_cast<double>(s->count), 500, 1) << label;
    EXPECT_EQ(s->gap_count, 0u) << label;
  }
}

TEST(RecordingReport, GrabFolderSegmentsAndCanSidecarsReadAsOneRecording) {
  // a roadslam-grab session folder: grab_000.rawlog, grab_001.rawlog and can_000/001.candump.log, here
  // made from the drive cut in two at 2.5 s (each half converted by roadslam-rawlog)
  const std::string dir = freshDir("grab");
  {
    roadslam::sources::PcapPacketSource in(drive() + "/velodyne.pcap");
    roadslam::pcap::PcapWriter a(dir + "/a.pcap"), b(dir + "/b.pcap");
    double t0 = -1;
    while (auto p = in.next()) {
      if (t0 < 0) t0 = p->stamp_s;
      (p->stamp_s - t0 < 2.5 ? a : b).writeUdp(p->stamp_s, p->dst_port, p->dst_port, p->payload.data(),
                                                p->payload.size(), p->src_ip);
    }
  }
  fs::create_directories(dir + "/session");
  for (const char* half : {"a", "b"}) {
    const std::string out = dir + "/session/grab_00" + (half[0] == 'a' ? "0" : "1") + ".rawlog";
    ASSERT_EQ(std::system((kBin + "/roadslam-rawlog convert " + dir + "/" + half + ".pcap " + out + " > /dev/null").c_str()), 0);
  }
  // the index sidecar a replay leaves beside a segment (rawlog_index.h) is no segment either
  fs::copy_file(dir + "/session/grab_000.rawlog", dir + "/session/grab_000.rawlog.idx");
  std::ifstream can(drive() + "/can.log");
  std::ofstream c0(dir + "/session/can_000.candump.log"), c1(dir + "/session/can_001.candump.log");
  std::string line;
  for (int n = 0; std::getline(can, line); ++n) (n < 700 ? c0 : c1) << line << "\n";
  c0.close(), c1.close();
  rr::ReportInputs in;
  in.recording = dir + "/session";
  const auto r = rr::buildReport(in);
  const auto whole = rr::buildReport(simInputs(drive() + "/velodyne.pcap"));
  ASSERT_EQ(r.files.size(), 2u) << "the .rawlog.ini and .rawlog.idx beside a segment are no segment";
  EXPECT_TRUE(r.damage.empty()) << r.damage;
  EXPECT_EQ(r.format, "rawlog");
  EXPECT_EQ(stream(r, "lidar")->count, stream(whole, "lidar")->count);
  EXPECT_EQ(stream(r, "lidar")->sweeps, stream(whole, "lidar")->sweeps);
  EXPECT_EQ(stream(r, "lidar")->gap_count, 0u) << "segments join without a hole";
  ASSERT_TRUE(r.can) << "the CAN sidecars, found without --can";
  EXPECT_EQ(r.can->frames, 1550u);
  EXPECT_EQ(r.can->ids.size(), 5u);
  EXPECT_TRUE(r.can->signals.empty()) << "no --vehicle: rates only";
}

TEST(RecordingReport, DamagedInputsNameThePlace) {
  const std::string dir = freshDir("damaged");
  std::ifstream src(drive() + "/velodyne.pcap", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(src)), std::istreambuf_iterator<char>());
  std::ofstream(dir + "/truncated.pcap", std::ios::binary) << bytes.substr(0, 300000);
  rr::ReportInputs in;
  in.recording = dir + "/truncated.pcap";
  const auto r = rr::buildReport(in);
  EXPECT_NE(r.damage.find("truncated.pcap"), std::string::npos) << r.damage;
  // the place by hand: pcap header 24 bytes, then records of a 16-byte header (incl_len at +8) and data
  size_t off = 24, record = 0;
  for (uint32_t incl = 0; off + 16 <= 300000; off += 16 + incl, ++record) {
    std::memcpy(&incl, bytes.data() + off + 8, 4);
    if (off + 16 + incl > 300000) break;
  }
  const std::string place = "record " + std::to_string(record) + " (byte " + std::to_string(off) + ")";
  EXPECT_NE(r.damage.find(place), std::string::npos) << r.damage << " vs " << place;
  EXPECT_GT(stream(r, "lidar")->count, 200u) << "reported up to the damage";
  // a rawlog cut in the middle: reported up to there, the place named as uncompressed byte and record count
  const std::string rawlog = dir + "/drive.rawlog";
  ASSERT_EQ(std::system((kBin + "/roadslam-rawlog convert " + drive() + "/velodyne.pcap " + rawlog + " > /dev/null").c_str()), 0);
  std::ifstream rf(rawlog, std::ios::binary);
  const std::string rbytes((std::istreambuf_iterator<char>(rf)), std::istreambuf_iterator<char>());
  std::ofstream(dir + "/cut.rawlog", std::ios::binary) << rbytes.substr(0, rbytes.size() / 2);
  in.recording = dir + "/cut.rawlog";
  const auto rc = rr::buildReport(in);
  EXPECT_NE(rc.damage.find("cut.rawlog"), std::string::npos) << rc.damage;
  EXPECT_NE(rc.damage.find("cut.rawlog: truncated record at uncompressed byte "), std::string::npos) << rc.damage;
  EXPECT_NE(rc.damage.find("records read before it"), std::string::npos) << rc.damage;
  EXPECT_GT(stream(rc, "lidar")->sweeps, 10u);
  EXPECT_LT(stream(rc, "lidar")->sweeps, 45u);
  std::ofstream(dir + "/random.rawlog", std::ios::binary) << std::string(5000, '\x5a');
  for (const std::string& bad : {dir + "/random.rawlog", dir + "/nope.pcap"}) {
    in.recording = bad;
    try {
      rr::buildReport(in);
      ADD_FAILURE() << bad << " accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
  // a CAN log with bad lines: counted, listed with their numbers; the good frames are used
  std::ifstream can(drive() + "/can.log");
  std::ofstream bad_can(dir + "/can.log");
  std::string line;
  for (int n = 1; std::getline(can, line); ++n) bad_can << (n == 3 || n == 10 ? "garbage line\n" : "") << line << "\n";
  bad_can << "(1700000004.9) can0 1A0#zz\n";
  bad_can.close();
  in = simInputs(drive() + "/velodyne.pcap");
  in.can_log = dir + "/can.log";
  const auto c = rr::buildReport(in);
  EXPECT_EQ(c.can->bad_lines, 3u);
  EXPECT_EQ(c.can->frames, 1550u);
  ASSERT_EQ(c.can->issues.size(), 3u);
  EXPECT_NE(c.can->issues[0].find("can.log:3:"), std::string::npos) << c.can->issues[0];
}

TEST(RecordingReport, MapFolderTrajectoryAndPicturesAreEmbedded) {
  const std::string dir = freshDir("map");
  fs::create_directories(dir + "/map");
  roadslam::datasets::Trajectory square;  // 30 m in three legs of 10 m
  for (const auto& [t, x, y] : std::vector<std::array<double, 3>>{{0, 0, 0}, {1, 10, 0}, {2, 10, 10}, {3, 0, 10}}) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() << x, y, 0;
    square.stamps_s.push_back(t);
    square.poses.push_back(T);
  }
  auto files = roadslam::runfolder::mapRunOfTrajectory(square, "test");
  files.summary["keyframes"] = 2;
  files.summary["other"] = 1;
  const std::string png("\x89PNG\r\n\x1a\n", 8);
  std::ofstream(dir + "/map/map_top.png", std::ios::binary) << png;
  roadslam::runfolder::writeMapRun(dir + "/map", files);
  auto in = simInputs(drive() + "/velodyne.pcap");
  in.map_dir = dir + "/map";
  const auto r = rr::buildReport(in);
  ASSERT_TRUE(r.map);
  EXPECT_EQ(r.map->poses, 4u);
  EXPECT_NEAR(r.map->length_m, 30.0, 1e-9);
  EXPECT_EQ(r.map->summary.value("keyframes", 0), 2);
  EXPECT_FALSE(r.map->summary.contains("other"));
  EXPECT_NE(rr::toHtml(r).find("data:image/png;base64,iVBORw0KGgo="), std::string::npos);
  in.map_dir = dir + "/nope";
  EXPECT_THROW(rr::buildReport(in), std::runtime_error);
  fs::remove(dir + "/map/run.json");  // as written before run folders had a manifest
  in.map_dir = dir + "/map";
  try {
    rr::buildReport(in);
    FAIL() << "a map folder without run.json must be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir + "/map/run.json: missing"), std::string::npos) << e.what();
  }
}

TEST(RecordingReport, AppWritesHtmlAndJsonThatChromiumRenders) {
  const std::string dir = freshDir("app");
  const std::string cmd = kBin + "/roadslam-report " + drive() + "/velodyne.pcap --can " + drive() +
                          "/can.log --vehicle " + kSrc + "/ini/vehicles/roadslam-sim.ini --out " + dir +
                          "/out > " + dir + "/stdout.txt 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::ifstream js(dir + "/out/report.json");
  const auto j = nlohmann::json::parse(js);
  EXPECT_EQ(j["streams"].size(), 3u);
  EXPECT_NEAR(j["streams"][0]["sweep_rate_hz"].get<double>(), 10.0, 0.05);
  EXPECT_EQ(j["can"]["ids"].size(), 5u);
  std::ifstream hs(dir + "/out/report.html");
  const std::string html((std::istreambuf_iterator<char>(hs)), std::istreambuf_iterator<char>());
  std::string fetched = html;  // nothing but the SVG namespace name may look like an address
  for (size_t p; (p = fetched.find("xmlns=\"http://www.w3.org/2000/svg\"")) != std::string::npos;) fetched.erase(p, 34);
  EXPECT_EQ(fetched.find("http://"), std::string::npos) << "opens offline";
  EXPECT_EQ(fetched.find("https://"), std::string::npos);
  EXPECT_EQ(std::system((kBin + "/roadslam-report " + dir + "/nope.pcap --out " + dir + "/o2 > " + dir +
                         "/err.txt 2>&1").c_str()) >> 8,
            1);
  if (std::system("command -v chromium > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "chromium is not installed (Debian: chromium)";
  const std::string png = dir + "/report.png";
  ASSERT_EQ(std::system(("chromium --headless --no-sandbox --disable-gpu --window-size=1200,2400 --screenshot=" + png +
                         " file://" + dir + "/out/report.html > /dev/null 2>&1").c_str()),
            0);
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 50000u) << "a page of tables and plots, not a blank one";
}

TEST(RecordingReport, RealCapturesAndCanLogMatchTheirManifests) {
  const std::string mrpt = kData + "/velodyne/mrpt_sample_velodyne_vlp16_gps.pcap";
  const std::string veloview = kData + "/velodyne/veloview_vlp-16-test-90deg-1-50-frames.pcap";
  const std::string civic = kData + "/can/civic-2019/civic_typeR_2019_turnonanddrive.candump.log";
  if (!fs::exists(mrpt) || !fs::exists(veloview) || !fs::exists(civic))
    GTEST_SKIP() << "real data not found under " << kData;
  rr::ReportInputs in;
  in.recording = mrpt;
  const auto a = rr::buildReport(in);
  EXPECT_EQ(stream(a, "lidar")->count, 293u);  // MANIFEST: 293 data + 57 position packets, 10 Hz
  EXPECT_EQ(stream(a, "gps")->count, 57u);
  EXPECT_EQ(stream(a, "lidar")->model, "vlp16");
  EXPECT_NEAR(stream(a, "lidar")->sweep_rate_hz, 10.0, 0.3);
  in.recording = veloview;
  in.lidar_model = "vlp16";  // its product byte says HDL-32E
  in.can_log = civic;        // another day: reported, with a warning
  const auto b = rr::buildReport(in);
  const auto* l = stream(b, "lidar");
  EXPECT_EQ(l->count, 1902u);  // MANIFEST: 1,902 data packets, 50 rotations at 20 Hz, ~755 packets/s
  EXPECT_NEAR(l->sweep_rate_hz, 20.0, 0.3);
  EXPECT_NEAR(l->rate_hz, 755, 5);
  EXPECT_EQ(l->drops, 0u) << "with the model forced, the VLP-16 packet clock has no holes";
  EXPECT_EQ(b.can->frames, 28835u);  // MANIFEST: 28,835 frames, 57 ids, 0x1D0 at ~12 Hz (logger drops)
  EXPECT_EQ(b.can->ids.size(), 57u);
  for (const auto& i : b.can->ids)
    if (i.id == 0x1D0) {
      EXPECT_NEAR(i.rate_hz, 12, 2);
    }
  EXPECT_GT(stream(b, "can")->gap_count + b.can->ids[0].gaps, 0u) << "irregular timing shows";
  ASSERT_EQ(b.warnings.size(), 1u);
  EXPECT_NE(b.warnings[0].find("does not overlap"), std::string::npos);
  // Left to the packets, the product byte's HDL-32E loses to their VLP-16 layout, with a warning:
  // the same model, packet period and drops as forced.
  in.lidar_model.clear();
  in.can_log.clear();
  const auto c = rr::buildReport(in);
  EXPECT_EQ(stream(c, "lidar")->model, "vlp16");
  EXPECT_EQ(stream(c, "lidar")->model_source, "packet layout");
  EXPECT_EQ(stream(c, "lidar")->drops, 0u);
  EXPECT_NEAR(stream(c, "lidar")->nominal_period_s, 1327.104e-6, 1e-9);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("but product byte 0x21 says HDL-32E; decoding as VLP-16; set --lidar-model hdl32 to force"),
            std::string::npos)
      << c.warnings[0];
}
